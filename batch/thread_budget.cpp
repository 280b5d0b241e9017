#include "batch/thread_budget.hpp"

#include <unistd.h>

#include <cstdlib>

#include <dlfcn.h>
#include <omp.h>

#include <algorithm>
#include <thread>

namespace ddafit::batch {

void bound_thread_spinning(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  ::setenv("GOMP_SPINCOUNT", "10000", 1);
  ::execv("/proc/self/exe", argv);
  // No /proc (or exec refused): run on with libgomp's default spinning.
}


void set_thread_budget(int threads) {
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  omp_set_num_threads(threads);
  // OpenBLAS is reached through CHOLMOD and may be another BLAS on a given machine, so
  // its setter is looked up rather than linked.
  using SetThreads = void (*)(int);
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
}

void set_worker_threads(int threads) { omp_set_num_threads(std::max(1, threads)); }

}  // namespace ddafit::batch
