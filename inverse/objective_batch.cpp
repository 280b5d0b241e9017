// Objective::evaluate_batch: independent points (a scan design, a profile's grid) run on
// `jobs` worker threads. The forward model shares nothing between runs (each copies the
// study's scene, sets its parameters and simulates it), so workers only need their own results slot; everything the
// Objective owns (log, cache, best point, progress) stays with the calling thread.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <stdexcept>
#include <mutex>
#include <set>
#include <thread>

#include "inverse/objective.hpp"

namespace ddafit::inverse {

std::vector<Evaluation> Objective::evaluate_batch(const std::vector<std::vector<double>>& points, int jobs) {
  if (batch_runner) return evaluate_batch(points, batch_runner);
  if (jobs <= 1) {
    std::vector<Evaluation> out;
    for (const auto& p : points) out.push_back(evaluate(p));
    return out;
  }
  // `jobs` threads take points in turn; their results queue up for the calling thread.
  const BatchRunner threads = [this, jobs](const std::vector<std::vector<double>>& todo, const RunDone& done) {
    struct Finished {
      size_t index;
      SimulationResult run;
      double seconds;
    };
    std::deque<Finished> queue;
    std::mutex mutex;
    std::condition_variable ready;
    // One run alone is made on the calling thread, with the process's whole thread budget
    // (a worker's is the budget over the jobs: a lone section VII run on one thread of two
    // would take half again as long).
    if (todo.size() == 1) {
      const auto t0 = std::chrono::steady_clock::now();
      SimulationResult run = scene_.run(todo[0], forward_);
      done(0, std::move(run), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      return;
    }
    std::atomic<size_t> next{0};
    const auto work = [&] {
      if (on_worker_start) on_worker_start();
      for (size_t i = next++; i < todo.size(); i = next++) {
        const auto t0 = std::chrono::steady_clock::now();
        SimulationResult run = scene_.run(todo[i], forward_);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::lock_guard<std::mutex> lock(mutex);
        queue.push_back({i, std::move(run), seconds});
        ready.notify_one();
      }
    };
    std::vector<std::thread> workers;
    for (int w = 0; w < std::min<int>(jobs, static_cast<int>(todo.size())); ++w) workers.emplace_back(work);
    // Recording may throw (a cache that cannot be written): the workers then take no new
    // point, finish the one they hold and are joined before the error goes on; a running
    // std::thread would otherwise end the process.
    try {
      for (size_t received = 0; received < todo.size(); ++received) {
        std::unique_lock<std::mutex> lock(mutex);
        ready.wait(lock, [&] { return !queue.empty(); });
        Finished f = std::move(queue.front());
        queue.pop_front();
        lock.unlock();
        done(f.index, std::move(f.run), f.seconds);
      }
    } catch (...) {
      next = todo.size();
      for (std::thread& t : workers) t.join();
      throw;
    }
    for (std::thread& t : workers) t.join();
  };
  return evaluate_batch(points, threads);
}

std::vector<Evaluation> Objective::evaluate_batch(const std::vector<std::vector<double>>& points,
                                                  const BatchRunner& runner) {
  // The points that need a forward run: neither seen in this process nor in the cache,
  // each once.
  std::vector<size_t> todo;
  std::set<std::string> keys;
  for (size_t k = 0; k < points.size(); ++k) {
    const std::string key = point_key(study_, points[k]);
    if (seen_.count(key) || !keys.insert(key).second || usable_cached(key)) continue;
    todo.push_back(k);
  }
  std::vector<std::vector<double>> todo_points;
  for (size_t k : todo) todo_points.push_back(points[k]);

  // Results arrive in any order; each point is recorded in the order of `points` as soon
  // as all before it are, so progress moves while runs finish.
  struct Slot {
    SimulationResult run;
    double seconds = 0.0;
    bool done = false;
  };
  std::vector<Slot> slots(todo.size());
  std::vector<Evaluation> out;
  size_t slot = 0;
  const auto record_ready = [&] {
    while (out.size() < points.size()) {
      const size_t k = out.size();
      if (slot < todo.size() && todo[slot] == k) {
        if (!slots[slot].done) return;
        out.push_back(record(points[k], &slots[slot].run, slots[slot].seconds));
        slots[slot].run = {};
        ++slot;
      } else {
        out.push_back(evaluate(points[k]));
      }
    }
  };
  record_ready();
  if (!todo_points.empty()) {
    // Runs under way: as many as run at a time, until fewer are left.
    const long at_a_time = std::max(1, jobs);
    long left = static_cast<long>(todo_points.size());
    running_ = std::min(at_a_time, left);
    runner(todo_points, [&](size_t i, SimulationResult run, double seconds) {
      slots[i] = {std::move(run), seconds, true};
      running_ = std::min(at_a_time, --left);
      record_ready();
    });
    running_ = 0;
  }
  record_ready();
  if (out.size() != points.size()) throw std::logic_error("evaluate_batch: the runner left points without a result");
  return out;
}

}  // namespace ddafit::inverse
