// The report's charts, as data files plus one gnuplot script (kept beside the PNGs so a
// user can restyle them).
#include <fmt/os.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "forward/io/gnuplot.hpp"
#include "inverse/report.hpp"

namespace ddafit::inverse {

bool plot_report(const std::string& dir, const Study& study, const InversionSummary& s, std::string& reason) {
  const std::filesystem::path d(dir);
  const auto path = [&](const char* name) { return (d / name).string(); };
  const std::string script = path("report.gp");
  auto gp = fmt::output_file(script);
  gp.print("set terminal pngcairo size 1200,800 font ',12'\nset grid\n");

  const BoundingFriction& f = s.friction;
  if (f.available && !f.profile.empty()) {
    double chi2_min = INFINITY;
    for (const ProfilePoint& p : f.profile) chi2_min = std::min(chi2_min, p.chi2);
    auto dat = fmt::output_file(path("profile.dat"));
    dat.print("# value delta_chi2 mu\n");
    for (const ProfilePoint& p : f.profile)
      if (!p.failed) dat.print("{:.17g} {:.17g} {:.17g}\n", p.value, p.chi2 - chi2_min, p.mu);
    dat.close();
    gp.print("set output '{}'\nset key top left noenhanced\n", path("profile.png"));
    // chi^2 on a log axis: the Delta = 1 and 4 levels stay visible beside a steep profile.
    gp.print("set xlabel '{}' noenhanced\nset ylabel 'chi2' noenhanced\nset logscale y\n",
             study.parameters[f.parameter].name);
    gp.print("set title 'mu_b = {:.4f} at the best fit; Delta chi2 <= 4: mu_b in [{:.4f}, {:.4f}]' noenhanced\n",
             f.mu_best, f.delta4.mu_low, f.delta4.mu_high);
    gp.print("plot '{}' using 1:($2+{:.17g}) with linespoints lw 2 pt 7 title 'profile', {:.17g} dt 2 lw 2 "
             "title 'chi2_min + 1', {:.17g} dt 3 lw 2 title 'chi2_min + 4'\nunset logscale y\n",
             path("profile.dat"), chi2_min, chi2_min + 1.0, chi2_min + 4.0);
  }

  if (s.best_level >= 0) {
    const Evaluation& e = s.levels[s.best_level].best;
    auto dat = fmt::output_file(path("fit.dat"));
    dat.print("# index label residual\n");
    for (size_t k = 0; k < study.observations.size(); ++k)
      dat.print("{} \"{} {}\" {:.17g}\n", k, study.observations[k].point, study.observations[k].quantity,
                k < e.residuals.size() ? e.residuals[k] : NAN);
    dat.close();
    gp.print("set output '{}'\nunset key\nset title 'best fit: (simulated - observed) / sigma' noenhanced\n",
             path("fit.png"));
    gp.print("set xlabel ''\nset ylabel 'residual (sigma)'\nset style fill solid 0.6\nset boxwidth 0.6\n");
    gp.print("set xtics rotate by -20 noenhanced\nset yrange [*<-2:2<*]\n");
    gp.print("plot '{}' using 1:3:xtic(2) with boxes, 1 dt 2 lc 'black', -1 dt 2 lc 'black'\n", path("fit.dat"));
    gp.print("set xtics norotate\nset autoscale y\nunset title\n");

    const std::vector<HistoryRow>& h = s.levels[s.best_level].history;
    if (!h.empty()) {
      // Axes follow the observations: lateral if the observed quantities are lateral.
      bool lateral_u = false, lateral_v = false;
      std::vector<std::string> points;
      for (const Observation& o : study.observations) {
        lateral_u = lateral_u || o.quantity == "max_lateral_displacement";
        lateral_v = lateral_v || o.quantity == "peak_lateral_velocity";
        if ((is_displacement(o.quantity) || is_velocity(o.quantity)) &&
            std::find(points.begin(), points.end(), o.point) == points.end())
          points.push_back(o.point);
      }
      auto dat2 = fmt::output_file(path("best_history.dat"));
      dat2.print("# time displacement speed (one block per row of scene measure points)\n");
      int max_point = 0;
      for (const HistoryRow& r : h) max_point = std::max(max_point, r.point);
      for (int pt = 0; pt <= max_point; ++pt) {
        for (const HistoryRow& r : h)
          if (r.point == pt)
            dat2.print("{:.9g} {:.9g} {:.9g}\n", r.time,
                       lateral_u ? std::abs(r.displacement.x()) : r.displacement.norm(),
                       lateral_v ? std::abs(r.velocity.x()) : r.velocity.norm());
        dat2.print("\n\n");
      }
      dat2.close();
      gp.print("set output '{}'\nset key outside right noenhanced\n", path("velocity_distance.png"));
      gp.print("set title 'best fit against the observations (dashed: observed, dotted: +-sigma)'\n");
      gp.print("set xlabel '{} (m)'\nset ylabel '{} (m/s)'\n", lateral_u ? "lateral displacement |u_x|" : "displacement |u|",
               lateral_v ? "lateral speed |v_x|" : "speed |v|");
      std::string plot = "plot ";
      // The history's point numbers are the scene's measure order; the summaries name them.
      const auto& names = e.point_names;
      for (size_t k = 0; k < names.size(); ++k)
        if (std::find(points.begin(), points.end(), names[k]) != points.end())
          plot += fmt::format("'{}' index {} using 2:3 with lines lw 2 title 'point {}', ", path("best_history.dat"), k,
                              names[k]);
      int arrows = 0;
      for (const Observation& o : study.observations) {
        if (!is_displacement(o.quantity) && !is_velocity(o.quantity)) continue;
        for (double v : {o.value - o.sigma, o.value, o.value + o.sigma}) {
          const char* style = v == o.value ? "dt 2 lw 2" : "dt 3 lw 1";
          if (is_displacement(o.quantity))
            gp.print("set arrow {} from first {:.9g}, graph 0 to first {:.9g}, graph 1 nohead {}\n", ++arrows, v, v, style);
          else
            gp.print("set arrow {} from graph 0, first {:.9g} to graph 1, first {:.9g} nohead {}\n", ++arrows, v, v, style);
        }
      }
      if (plot.size() > 5) gp.print("{}\n", plot.substr(0, plot.size() - 2));
    }
  }
  gp.close();
  return io::run_gnuplot(script, "report.md and report.json", reason);
}

}  // namespace ddafit::inverse
