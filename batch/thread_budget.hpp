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

// Threads that wait must not spin when the machine is shared. GNU OpenMP's idle threads spin
// up to GOMP_SPINCOUNT (default 300 000) times before they sleep: two Vajont section I runs
// started together on the 2-core machine each took 3.9x their solo wall (39.7 s against
// 10.1 s), the spinning threads of one stealing the cores the other's work needed. With
// 10 000 the pair takes 2.0x (20.6-21.7 s against 10.8 s solo; docs/performance.md). libgomp
// reads the setting once, when it is loaded, so when neither OMP_WAIT_POLICY nor
// GOMP_SPINCOUNT is set this re-executes the program once with GOMP_SPINCOUNT=10000; a
// user's own setting is kept. Call first thing in main().
void bound_thread_spinning(char** argv);

// The OpenMP threads of the calling thread's model runs (a worker of `scan --jobs`): each
// std::thread starts with the default, not the main thread's budget.
void set_worker_threads(int threads);

}  // namespace ddafit::batch
