#include "apps/ddafit/plots.hpp"

#include <fmt/os.h>

#include <cstdlib>
#include <filesystem>

namespace ddafit::app {

bool run_gnuplot(const std::string& script_path, std::string& reason) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    reason = "gnuplot is not installed (apt-get install gnuplot-nox); the data files are written";
    return false;
  }
  const std::string cmd = "gnuplot '" + script_path + "' 2> '" + script_path + ".log'";
  if (std::system(cmd.c_str()) != 0) {
    reason = "gnuplot failed; see " + script_path + ".log";
    return false;
  }
  return true;
}

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
  return run_gnuplot(script, reason);
}

bool plot_history(const std::string& dir, const Scene& scene, std::string& reason) {
  const std::filesystem::path d(dir);
  const std::string csv = (d / "history.csv").string();
  const std::string script = (d / "history.gp").string();
  {
    auto gp = fmt::output_file(script);
    gp.print("set datafile separator ','\nset terminal pngcairo size 1200,800 font ',12'\nset key outside right\n");
    gp.print("set grid\n");
    // Column numbers of history.csv: time 1, point 2, x 3, y 4, ux 5, uy 6, vx 7, vy 8.
    // Rows come time by time, one per point in scene order, so point k is every n-th
    // row from row k (a filter on the name would break each line at the other rows).
    const size_t n = scene.measure.size();
    const auto curves = [&](const std::string& x, const std::string& y) {
      std::string plot = "plot ";
      for (size_t k = 0; k < n; ++k)
        plot += fmt::format("{}'{}' skip 1 every {}::{} using ({}):({}) with lines lw 2 title '{}'", k ? ", " : "",
                            csv, n, k, x, y, scene.measure[k].name);
      return plot + "\n";
    };
    gp.print("set output '{}'\nset xlabel 'time (s)'\nset ylabel 'distance |u| (m)'\n", (d / "distance_time.png").string());
    gp.print("{}", curves("$1", "sqrt($5**2+$6**2)"));
    gp.print("set output '{}'\nset ylabel 'speed |v| (m/s)'\n", (d / "velocity_time.png").string());
    gp.print("{}", curves("$1", "sqrt($7**2+$8**2)"));
    gp.print("set output '{}'\nset xlabel 'distance |u| (m)'\nset ylabel 'speed |v| (m/s)'\n",
             (d / "velocity_distance.png").string());
    gp.print("{}", curves("sqrt($5**2+$6**2)", "sqrt($7**2+$8**2)"));
  }
  return run_gnuplot(script, reason);
}

}  // namespace ddafit::app
