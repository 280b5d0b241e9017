// The files a run leaves in its output folder: history.csv and summary.json.
#pragma once

#include <string>

#include "forward/simulation.hpp"

namespace ddafit::app {

// header: time,point,x,y,ux,uy,vx,vy (one row per measure point per output time)
void write_history_csv(const std::string& path, const Scene& scene, const SimulationResult& result);

void write_summary_json(const std::string& path, const std::string& scene_path, const SimulationResult& result);

}  // namespace ddafit::app
