// A forward run's result as text: the part the objective reads (status, message, the
// points' summaries, simulated and wall time). It crosses from an MPI worker's child to
// rank 0, and from a SLURM array task's file to `scan --collect`.
#pragma once

#include <string>

#include "forward/simulation.hpp"

namespace ddafit::app {

std::string encode_run(const SimulationResult& run, double seconds);
// Throws nlohmann::json's exceptions on text that is not an encoded run.
SimulationResult decode_run(const std::string& text, double* seconds);

}  // namespace ddafit::app
