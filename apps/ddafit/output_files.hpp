// The files a run leaves in its output folder: history.csv and summary.json.
#pragma once

#include <string>

#include "forward/simulation.hpp"

namespace ddafit::app {

// Creates the output folder `out` if needed and checks that a file can be written in it.
// Empty when it can; otherwise one line, "OUT: --out: PROBLEM" (a read-only folder, a
// path through a regular file, a name the file system refuses).
std::string prepare_output_folder(const std::string& out);

// A wall time for progress lines: "4m07s", or "2h13m" from an hour up.
std::string clock_text(double seconds);

// header: time,point,x,y,ux,uy,vx,vy (one row per measure point per output time)
void write_history_csv(const std::string& path, const Scene& scene, const SimulationResult& result);

void write_summary_json(const std::string& path, const std::string& scene_path, const SimulationResult& result);

}  // namespace ddafit::app
