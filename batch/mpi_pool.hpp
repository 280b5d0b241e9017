// Scans and ensembles under `mpirun -n K ddafit scan ...` (or `simulate --ensemble`): rank 0
// runs the command as it would alone and hands its forward runs to ranks 1..K-1. Each worker makes a run in a child process, so a
// run that crashes or hangs costs that run (retried once, then recorded as failed), never
// the job. Results come back as the run's summary; the cache on rank 0 is the one writer.
#pragma once

#include <string>

#include "inverse/objective.hpp"
#include "inverse/study.hpp"

namespace ddafit::batch {

// Whether this process was started by mpirun (OpenMPI or PMI(x) variables are set).
bool mpi_launched();

struct MpiWorld {
  int rank = 0;
  int size = 1;
};
// MPI_Init when launched by mpirun (else rank 0 of 1, no MPI); mpi_stop() ends it.
MpiWorld mpi_start(int* argc, char*** argv);
void mpi_stop();

// Rank 0: the batch runner that sends points to the workers and collects their results.
inverse::Objective::BatchRunner mpi_batch_runner(const MpiWorld& world);
// Rank 0, at the end: tells every worker to stop.
void mpi_release_workers(const MpiWorld& world);

// Ranks > 0: run points for rank 0 until it says stop. `threads` per run; a run longer
// than `timeout_seconds` is killed. A point with one value more than the study has
// parameters is realisation (that value) of the model spread (inverse/model_spread.hpp).
void mpi_worker(const inverse::Study& study, int threads, double timeout_seconds);

// Ranks > 0 of `simulate --ensemble` under mpirun: each point rank 0 sends is one value,
// the realisation of `scene` to run (forward/perturb.hpp).
void mpi_ensemble_worker(const Scene& scene, int threads, double timeout_seconds);

}  // namespace ddafit::batch
