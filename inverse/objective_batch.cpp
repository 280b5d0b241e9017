// Objective::evaluate_batch: independent points (a scan design, a profile's grid) run on
// `jobs` worker threads. The forward model shares nothing between runs (a scene is read
// and simulated per call), so workers only need their own results slot; everything the
// Objective owns (log, cache, best point, progress) stays with the calling thread.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <set>
#include <thread>

#include "inverse/objective.hpp"

namespace ddafit::inverse {

std::vector<Evaluation> Objective::evaluate_batch(const std::vector<std::vector<double>>& points, int jobs) {
  std::vector<Evaluation> out;
  // The points that need a forward run: neither seen in this process nor in the cache,
  // each once.
  std::vector<size_t> todo;
  std::set<std::string> keys;
  for (size_t k = 0; k < points.size(); ++k) {
    const std::string key = point_key(study_, points[k]);
    if (seen_.count(key) || !keys.insert(key).second || cache_.find(key)) continue;
    todo.push_back(k);
  }
  if (jobs <= 1 || todo.size() <= 1) {
    for (const auto& p : points) out.push_back(evaluate(p));
    return out;
  }

  struct Slot {
    SimulationResult run;
    double seconds = 0.0;
    bool done = false;
  };
  std::vector<Slot> slots(todo.size());
  std::mutex mutex;
  std::condition_variable finished;
  std::atomic<size_t> next{0};
  const auto work = [&] {
    if (on_worker_start) on_worker_start();
    for (size_t i = next++; i < todo.size(); i = next++) {
      const auto t0 = std::chrono::steady_clock::now();
      SimulationResult run = run_guarded(forward_, study_.scene_path, point_overrides(study_, points[todo[i]]));
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::lock_guard<std::mutex> lock(mutex);
      slots[i].run = std::move(run);
      slots[i].seconds = seconds;
      slots[i].done = true;
      finished.notify_all();
    }
  };
  std::vector<std::thread> workers;
  for (int w = 0; w < std::min<int>(jobs, static_cast<int>(todo.size())); ++w) workers.emplace_back(work);

  // Record in the order of `points`, each run as soon as it is there.
  size_t slot = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    if (slot < todo.size() && todo[slot] == k) {
      std::unique_lock<std::mutex> lock(mutex);
      finished.wait(lock, [&] { return slots[slot].done; });
      SimulationResult run = std::move(slots[slot].run);
      const double seconds = slots[slot].seconds;
      lock.unlock();
      out.push_back(record(points[k], &run, seconds));
      ++slot;
    } else {
      out.push_back(evaluate(points[k]));
    }
  }
  for (std::thread& t : workers) t.join();
  return out;
}

}  // namespace ddafit::inverse
