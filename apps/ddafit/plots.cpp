#include "apps/ddafit/plots.hpp"

#include <fmt/os.h>

#include <cstdlib>
#include <filesystem>

#include "forward/io/gnuplot.hpp"
#include "forward/io/html_report.hpp"
#include "forward/model_revision.hpp"

namespace ddafit::app {

bool plot_blocks(const std::string& dir, const Scene& scene, std::string& reason) {
  const std::filesystem::path d(dir);
  {
    auto free_blocks = fmt::output_file((d / "blocks_free.dat").string());
    auto fixed_blocks = fmt::output_file((d / "blocks_fixed.dat").string());
    for (const BlockInput& b : scene.blocks) {
      auto& out = b.fixed ? fixed_blocks : free_blocks;
      for (const Vec2& p : b.polygon) out.print("{:.9g} {:.9g}\n", p.x(), p.y());
      out.print("{:.9g} {:.9g}\n\n", b.polygon.front().x(), b.polygon.front().y());
    }
  }
  const std::string script = (d / "blocks.gp").string();
  {
    auto gp = fmt::output_file(script);
    gp.print("set terminal pngcairo size 1800,1000 font ',12'\nset output '{}'\n", (d / "blocks.png").string());
    gp.print("set size ratio -1\nset xlabel 'x (m)'\nset ylabel 'y (m)'\nunset key\n");
    gp.print("set title '{} blocks'\n", scene.blocks.size());
    gp.print("plot '{}' with filledcurves lc rgb '#cccccc', '{}' with lines lc rgb '#202020' lw 0.6\n",
             (d / "blocks_fixed.dat").string(), (d / "blocks_free.dat").string());
  }
  return io::run_gnuplot(script, "the data files", reason);
}

namespace {

// Quotes for a gnuplot single-quoted string: a quote is doubled.
std::string gnuplot_text(std::string text) {
  for (size_t k = text.find('\''); k != std::string::npos; k = text.find('\'', k + 2)) text.insert(k, 1, '\'');
  return text;
}

void write_outlines(const std::string& path, const std::vector<std::vector<Vec2>>& polygons) {
  auto out = fmt::output_file(path);
  for (const std::vector<Vec2>& polygon : polygons) {
    for (const Vec2& p : polygon) out.print("{:.9g} {:.9g}\n", p.x(), p.y());
    if (!polygon.empty()) out.print("{:.9g} {:.9g}\n\n", polygon.front().x(), polygon.front().y());
  }
}

}  // namespace

bool plot_configuration(const std::string& dir, const Scene& scene, const std::vector<std::vector<Vec2>>& final_blocks,
                        const std::string& title, std::string& reason) {
  const std::filesystem::path d(dir);
  std::vector<std::vector<Vec2>> fixed, initial;
  for (const BlockInput& b : scene.blocks) (b.fixed ? fixed : initial).push_back(b.polygon);
  write_outlines((d / "configuration_fixed.dat").string(), fixed);
  write_outlines((d / "configuration_initial.dat").string(), initial);
  write_outlines((d / "configuration_final.dat").string(), final_blocks);
  const std::string script = (d / "configuration.gp").string();
  {
    auto gp = fmt::output_file(script);
    gp.print("set terminal pngcairo size 1800,1000 font ',12'\nset output '{}'\n", (d / "configuration.png").string());
    gp.print("set size ratio -1\nset xlabel 'x (m)'\nset ylabel 'y (m)'\nset key outside below\n");
    gp.print("set title '{}: blocks at the start and at the end of the run'\n", gnuplot_text(title));
    const double width = initial.size() > 500 ? 0.3 : 0.8;
    gp.print("plot '{}' with filledcurves lc rgb '#dddddd' title 'fixed', '{}' with lines lc rgb '#9ab0c8' lw {} "
             "title 'start', '{}' with lines lc rgb '#202020' lw {} title 'end'\n",
             (d / "configuration_fixed.dat").string(), (d / "configuration_initial.dat").string(), width,
             (d / "configuration_final.dat").string(), width);
  }
  return io::run_gnuplot(script, "the data files", reason);
}

bool plot_history(const std::string& dir, const Scene& scene, const std::string& title, std::string& reason,
                  const ObservedRanges& observed) {
  const std::filesystem::path d(dir);
  const std::string csv = (d / "history.csv").string();
  const std::string script = (d / "history.gp").string();
  {
    auto gp = fmt::output_file(script);
    gp.print("set datafile separator ','\nset terminal pngcairo size 1200,800 font ',12'\nset key outside right\n");
    gp.print("set grid\n");
    const std::string name = gnuplot_text(title);
    // Column numbers of history.csv: time 1, point 2, x 3, y 4, ux 5, uy 6, vx 7, vy 8.
    // Rows come time by time, one per point in scene order, so point k is every n-th
    // row from row k (a filter on the name would break each line at the other rows).
    const size_t n = scene.measure.size();
    const auto curves = [&](const std::string& x, const std::string& y) {
      std::string plot = "plot ";
      for (size_t k = 0; k < n; ++k)
        // gnuplot cycles 8 colours: the 9th point on is dashed, so no two curves look alike.
        plot += fmt::format("{}'{}' skip 1 every {}::{} using ({}):({}) with lines lw 2 dt {} title '{}' noenhanced",
                            k ? ", " : "", csv, n, k, x, y, k / 8 + 1, gnuplot_text(scene.measure[k].name));
      return plot + "\n";
    };
    gp.print("set output '{}'\nset title '{}: distance against time'\nset xlabel 'time (s)'\n"
             "set ylabel 'distance |u| (m)'\n", (d / "distance_time.png").string(), name);
    gp.print("{}", curves("$1", "sqrt($5**2+$6**2)"));
    gp.print("set output '{}'\nset title '{}: lateral runout against time'\nset ylabel 'lateral runout |u_x| (m)'\n",
             (d / "runout_time.png").string(), name);
    gp.print("{}", curves("$1", "abs($5)"));
    gp.print("set output '{}'\nset title '{}: speed against time'\nset ylabel 'speed |v| (m/s)'\n",
             (d / "velocity_time.png").string(), name);
    gp.print("{}", curves("$1", "sqrt($7**2+$8**2)"));
    gp.print("set output '{}'\nset title '{}: speed against distance'\nset xlabel 'distance |u| (m)'\n"
             "set ylabel 'speed |v| (m/s)'\n", (d / "velocity_distance.png").string(), name);
    gp.print("{}", curves("sqrt($5**2+$6**2)", "sqrt($7**2+$8**2)"));
    // Seed Fig. 14: lateral speed against lateral runout, with a field estimate as bands
    // (gnuplot objects behind the curves; a dummy curve per band puts it in the legend).
    gp.print("set output '{}'\nset title '{}: lateral speed against lateral runout'\n"
             "set xlabel 'lateral runout |u_x| (m)'\nset ylabel 'lateral speed |v_x| (m/s)'\n",
             (d / "velocity_distance_lateral.png").string(), name);
    gp.print("set key outside below maxrows 4\n");
    std::string legend;
    const std::string who = gnuplot_text(observed.label.empty() ? std::string("estimate") : observed.label);
    if (observed.runout.size() == 2) {
      // "[0 : X < *]": autoscaled, but far enough to show the whole band.
      gp.print("set xrange [0 : {:g} < *]\n", 1.05 * observed.runout[1]);
      gp.print("set object 1 rect from first {}, graph 0 to first {}, graph 1 behind fc rgb '#f4d6a0' fs solid 0.6 "
               "noborder\n", observed.runout[0], observed.runout[1]);
      legend += fmt::format(", NaN with boxes fs solid 0.6 fc rgb '#f4d6a0' title '{}: runout {:g}-{:g} m' noenhanced",
                            who, observed.runout[0], observed.runout[1]);
    }
    if (observed.peak_speed.size() == 2) {
      gp.print("set yrange [0 : {:g} < *]\n", 1.05 * observed.peak_speed[1]);
      gp.print("set object 2 rect from graph 0, first {} to graph 1, first {} behind fc rgb '#b8d8ec' fs solid 0.6 "
               "noborder\n", observed.peak_speed[0], observed.peak_speed[1]);
      legend += fmt::format(
          ", NaN with boxes fs solid 0.6 fc rgb '#b8d8ec' title '{}: peak speed {:g}-{:g} m/s' noenhanced", who,
          observed.peak_speed[0], observed.peak_speed[1]);
    }
    std::string lateral = curves("abs($5)", "abs($7)");
    lateral.insert(lateral.size() - 1, legend);
    gp.print("{}", lateral);
  }
  return io::run_gnuplot(script, "the data files", reason);
}

}  // namespace ddafit::app

namespace ddafit::app {

void write_run_report(const std::string& dir, const std::string& label, const SimulationResult& result) {
  const SimulationSummary& s = result.summary;
  io::HtmlReport page;
  page.title = "Run: " + label;
  if (s.points.empty()) {
    page.headline = fmt::format("The run completed {:.2f} s; the scene has no measure point.", s.run.simulated_time);
  } else {
    const PointSummary& p = s.points.front();
    page.headline = fmt::format(
        "Point {} ran {:.1f} m ({:.1f} m laterally) at up to {:.2f} m/s in {:.2f} s simulated; {}.", p.name,
        p.max_total_displacement, p.max_lateral_displacement, p.peak_total_velocity, s.run.simulated_time,
        p.stopped ? fmt::format("it came to rest by {:.2f} s", p.duration) : std::string("it was still moving at the end"));
  }
  std::string md = "## Measure points\n\n| point | max lateral displacement (m) | max total displacement (m) | peak "
                   "lateral speed (m/s) | peak speed (m/s) | moving until (s) | at rest at the end |\n"
                   "|---|---|---|---|---|---|---|\n";
  for (const PointSummary& p : s.points)
    md += fmt::format("| {} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.3g} | {} |\n", p.name, p.max_lateral_displacement,
                      p.max_total_displacement, p.peak_lateral_velocity, p.peak_total_velocity, p.duration,
                      p.stopped ? "yes" : "no");
  if (!s.warnings.empty()) {
    md += "\n## Warnings\n\n";
    for (const std::string& w : s.warnings) md += "- " + w + "\n";
  }
  md += "\n## Charts\n\n![configuration](configuration.png)\n![velocity against distance](velocity_distance.png)\n"
        "![lateral velocity against lateral runout](velocity_distance_lateral.png)\n![distance against time]"
        "(distance_time.png)\n![velocity against time](velocity_time.png)\n![runout against time](runout_time.png)\n";
  page.markdown = md;
  page.embed_other_charts = false;
  page.settings = {{"scene", label},
                   {"solver", std::string(to_string(s.solver.integrator)) + " (" + s.solver.reason + ")"},
                   {"steps", std::to_string(s.run.steps)},
                   {"worst overlap (of the smaller block)", fmt::format("{:.3g} %", 100.0 * s.solver.worst_penetration_ratio)},
                   {"model revision", kModelRevision}};
  io::write_html_report(dir, page);
}

}  // namespace ddafit::app
