// PNG charts drawn by gnuplot (a runtime tool: when it is missing the charts are skipped
// with a note, the data files stay).
#pragma once

#include <string>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit::app {

// Runs gnuplot on a script; returns false (with a reason) when it cannot.
bool run_gnuplot(const std::string& script_path, std::string& reason);

// blocks.png: free blocks outlined, fixed blocks shaded.
bool plot_blocks(const std::string& dir, const Scene& scene, std::string& reason);

// From DIR/history.csv: distance_time.png, runout_time.png (lateral), velocity_time.png,
// velocity_distance.png (the seed's Fig. 11-12 panels), one curve per measurement point,
// titled with `title` (the scene), legends outside the plot.
bool plot_history(const std::string& dir, const Scene& scene, const std::string& title, std::string& reason);

// configuration.png: the blocks at t = 0 (grey) and at the end of the run (`final_blocks`,
// dark), fixed blocks shaded: the seed's Fig. 13.
bool plot_configuration(const std::string& dir, const Scene& scene, const std::vector<std::vector<Vec2>>& final_blocks,
                        const std::string& title, std::string& reason);

}  // namespace ddafit::app
