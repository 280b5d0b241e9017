// PNG charts drawn by gnuplot (a runtime tool: when it is missing the charts are skipped
// with a note, the data files stay).
#pragma once

#include <string>

#include "forward/scene.hpp"

namespace ddafit::app {

// Runs gnuplot on a script; returns false (with a reason) when it cannot.
bool run_gnuplot(const std::string& script_path, std::string& reason);

// blocks.png: free blocks outlined, fixed blocks shaded.
bool plot_blocks(const std::string& dir, const Scene& scene, std::string& reason);

// From DIR/history.csv: distance_time.png, velocity_time.png, velocity_distance.png
// (the seed's Fig. 11-12 panels), one curve per measurement point.
bool plot_history(const std::string& dir, const Scene& scene, std::string& reason);

}  // namespace ddafit::app
