// PNG charts drawn by gnuplot (a runtime tool: when it is missing the charts are skipped
// with a note, the data files stay).
#pragma once

#include <string>
#include <vector>

#include "forward/run_summary.hpp"
#include "forward/scene.hpp"

namespace ddafit::app {

// blocks.png: free blocks outlined, fixed blocks shaded.
bool plot_blocks(const std::string& dir, const Scene& scene, std::string& reason);

// A field estimate to draw beside a run: lateral runout and peak lateral speed ranges
// (e.g. Hendron & Patton's 400-500 m and 20-25 m/s for Vajont). Empty ranges are not drawn.
struct ObservedRanges {
  std::string label;                // legend text, e.g. "Hendron & Patton (1985)"
  std::vector<double> runout;       // m, {low, high}
  std::vector<double> peak_speed;   // m/s, {low, high}
};

// From DIR/history.csv: distance_time.png, runout_time.png (lateral), velocity_time.png,
// velocity_distance.png (the seed's Fig. 11-12 panels) and velocity_distance_lateral.png
// (lateral speed against lateral runout, the seed's Fig. 14, with `observed` as shaded
// bands), one curve per measurement point, titled with `title` (the scene), legends
// outside the plot.
bool plot_history(const std::string& dir, const Scene& scene, const std::string& title, std::string& reason,
                  const ObservedRanges& observed = {});

// configuration.png: the blocks at t = 0 (grey) and at the end of the run (`final_blocks`,
// dark), fixed blocks shaded: the seed's Fig. 13.
bool plot_configuration(const std::string& dir, const Scene& scene, const std::vector<std::vector<Vec2>>& final_blocks,
                        const std::string& title, std::string& reason);

// report.html of `simulate --plots` (forward/io/html_report.hpp): the run's status and
// point 1's runout as the headline, the per-point table, the charts above embedded, the
// scene, solver and model revision. Throws std::runtime_error when it cannot be written.
void write_run_report(const std::string& dir, const std::string& label, const SimulationResult& result);

}  // namespace ddafit::app
