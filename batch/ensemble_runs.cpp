#include "batch/ensemble_runs.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

#include "batch/thread_budget.hpp"
#include "forward/simulation.hpp"

namespace ddafit::batch {

EnsembleRuns ensemble_runs(int members, int jobs, int threads) {
  EnsembleRuns runs;
  runs.members = members;
  runs.jobs = std::max(1, jobs);
  const int cores = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  runs.threads_per_run = std::max(1, cores / runs.jobs);
  return runs;
}

std::vector<SimulationResult> run_ensemble(const Scene& scene, const EnsembleRuns& runs) {
  std::vector<SimulationResult> results(static_cast<size_t>(std::max(runs.members, 0)));
  std::vector<int> todo = runs.realisations;
  if (todo.empty())
    for (int k = 0; k < runs.members; ++k) todo.push_back(k);
  const int count = static_cast<int>(todo.size());
  const auto member = [&](int k) {
    Scene nudged = scene;
    nudged.options.realisation = k;
    return simulate(nudged);
  };
  if (runs.jobs <= 1) {
    for (const int k : todo) {
      results[k] = member(k);
      if (runs.on_member) runs.on_member(k, results[k]);
    }
    return results;
  }
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<int> finished;
  std::atomic<int> next{0};
  const auto work = [&] {
    set_worker_threads(runs.threads_per_run);
    for (int i = next++; i < count; i = next++) {
      SimulationResult r = member(todo[i]);
      std::lock_guard<std::mutex> lock(mutex);
      results[todo[i]] = std::move(r);
      finished.push_back(todo[i]);
      ready.notify_one();
    }
  };
  std::vector<std::thread> workers;
  for (int w = 0; w < std::min(runs.jobs, count); ++w) workers.emplace_back(work);
  for (int received = 0; received < count; ++received) {
    std::unique_lock<std::mutex> lock(mutex);
    ready.wait(lock, [&] { return !finished.empty(); });
    const int k = finished.front();
    finished.pop_front();
    lock.unlock();
    if (runs.on_member) runs.on_member(k, results[k]);
  }
  for (std::thread& t : workers) t.join();
  return results;
}

}  // namespace ddafit::batch
