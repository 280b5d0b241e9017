// One thread budget for a process that runs the model: OpenMP (the substep solver's
// sweeps, CHOLMOD's supernodal factorisation) and OpenBLAS share it instead of each
// starting a thread per core.
#pragma once

namespace ddafit::batch {

// threads: OpenMP threads; 0 = the core count. BLAS is held to one thread: on a
// 1621-block wall CHOLMOD with OpenBLAS's own threads beside OpenMP's spent more time in
// the kernel than in user code and took 1.8x as long (docs/performance.md), and a second
// BLAS thread gains 0-10 % on these bandwidth-bound factorisations (field notes).
void set_thread_budget(int threads);

// The OpenMP threads of the calling thread's model runs (a worker of `scan --jobs`): each
// std::thread starts with the default, not the main thread's budget.
void set_worker_threads(int threads);

}  // namespace ddafit::batch
