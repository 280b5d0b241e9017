// The files a run leaves in its output folder: history.csv, summary.json, and stable.json
// of a stable-angle search. The command line and the Python module both write them here.
#pragma once

#include <string>

#include <vector>

#include "forward/analysis/ensemble.hpp"
#include "forward/analysis/stable_friction.hpp"
#include "forward/run_summary.hpp"
#include "forward/scene.hpp"

namespace ddafit::io {

// Creates the output folder `out` if needed and checks that a file can be written in it.
// Empty when it can; otherwise one line, "OUT: --out: PROBLEM" (a read-only folder, a
// path through a regular file, a name the file system refuses).
std::string prepare_output_folder(const std::string& out);

// header: time,point,x,y,ux,uy,vx,vy (one row per measure point per output time)
void write_history_csv(const std::string& path, const Scene& scene, const SimulationResult& result);

// summary.json: status, warnings, each point's quantities, the run's counters, the solver's
// report and the wall time of each stage. Throws std::runtime_error when it cannot write.
void write_summary_json(const std::string& path, const std::string& scene_path, const SimulationResult& result);
// summary.json's text (what the Python module returns as a dict).
std::string summary_json_text(const std::string& scene_path, const SimulationResult& result);

// What a stable search was asked: for stable.json.
struct StableSearchInput {
  std::string scene_path;
  std::string interface;
  double rest_speed = 0.0;  // the scene's, m/s
  StableSearchOptions options;
};

// stable.json: the criterion and its numbers, the bracket of the stable friction angle and
// every trial. Throws std::runtime_error when it cannot write.
void write_stable_json(const std::string& path, const StableSearchInput& input, const StableSearchResult& result);
std::string stable_json_text(const StableSearchInput& input, const StableSearchResult& result);

// ensemble.json: per measure point and quantity, the mean, standard deviation and range
// over the completed members, with the jitter rule. ensemble.csv: one row per member and
// point (realisation, status, point, the quantities). Throw std::runtime_error when they
// cannot be written.
void write_ensemble_json(const std::string& path, const std::string& scene_path, const EnsembleSummary& ensemble);
void write_ensemble_csv(const std::string& path, const std::vector<SimulationResult>& members);

}  // namespace ddafit::io
