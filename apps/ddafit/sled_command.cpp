// `ddafit sled SCENE --out DIR`: the slide at fidelity 0 (forward/sled/sled.hpp): the free
// blocks as one flexible sled along the ground, in well under a second. Writes sled.csv (its
// distance and speed along the path), sled.json (the static friction angle and the run's
// extremes), sled.png (velocity against distance) and the usual history.csv / summary.json.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "forward/io/gnuplot.hpp"
#include "forward/io/run_files.hpp"
#include "forward/simulation.hpp"

namespace ddafit::app {
namespace {

void write_sled_files(const std::string& dir, const std::string& scene_path, const SimulationResult& r) {
  const std::filesystem::path out(dir);
  {
    std::ofstream csv(out / "sled.csv");
    csv << "time,distance,velocity\n";
    for (const SledPoint& p : r.sled.series) csv << fmt::format("{:.9g},{:.9g},{:.9g}\n", p.time, p.distance, p.velocity);
  }
  double peak = 0.0, stop = 0.0;
  for (const SledPoint& p : r.sled.series) {
    peak = std::max(peak, std::abs(p.velocity));
    if (std::abs(p.velocity) > 0.0) stop = p.time;
  }
  const SledPoint last = r.sled.series.empty() ? SledPoint{} : r.sled.series.back();
  nlohmann::ordered_json j;
  j["scene"] = scene_path;
  j["status"] = r.summary.status == RunStatus::Completed ? "completed" : "failed";
  j["static_friction_angle"] = r.sled.static_friction_angle;
  j["static_friction_angle_note"] =
      "deg: the basal friction angle at which the sled is just stable, atan(sum m sin b / sum m cos b)";
  j["slices"] = r.sled.slices;
  j["path_length"] = r.sled.path_length;
  j["distance"] = last.distance;
  j["peak_velocity"] = peak;
  j["moving_until"] = stop;
  j["stopped"] = last.velocity == 0.0;
  std::ofstream(out / "sled.json") << j.dump(2) << "\n";
  const std::string folder = std::filesystem::absolute(out).string();
  std::ofstream gp(out / "sled.gp");
  gp << "set terminal pngcairo size 900,600\nset output '" << folder << "/sled.png'\nset datafile separator ','\n"
     << "set xlabel 'distance along the path (m)'\nset ylabel 'velocity (m/s)'\nset grid\n"
     << "plot '" << folder << "/sled.csv' skip 1 using 2:3 with lines lw 2 title 'sled'\n";
}

}  // namespace

int run_sled(const SledArgs& args) {
  Scene scene;
  if (!load_scene(args.scene, args.sets, scene)) return kExitBadInput;
  scene.options.integrator = Integrator::Sled;
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  const SimulationResult r = simulate(scene);
  if (r.summary.status == RunStatus::InvalidScene) {
    std::cerr << args.scene << ": " << r.summary.message << "\n";
    return kExitBadInput;
  }
  const std::filesystem::path out(args.out);
  io::write_history_csv((out / "history.csv").string(), scene, r);
  io::write_summary_json((out / "summary.json").string(), args.scene, r);
  write_sled_files(args.out, args.scene, r);
  std::string why;
  if (!io::run_gnuplot((out / "sled.gp").string(), "sled.csv", why)) std::cerr << "note: " << why << "\n";
  for (const std::string& w : r.summary.warnings) std::cerr << "warning: " << w << "\n";
  const SledPoint last = r.sled.series.empty() ? SledPoint{} : r.sled.series.back();
  std::cout << fmt::format("sled: {} slices over a {:.1f} m path; static friction angle {:.2f} deg\n", r.sled.slices,
                           r.sled.path_length, r.sled.static_friction_angle);
  std::cout << fmt::format("moved {:.1f} m in {:.1f} s, {}; wrote {}/sled.csv, sled.json, sled.png\n", last.distance,
                           last.time, last.velocity == 0.0 ? "at rest at the end" : "still moving at the end",
                           args.out);
  return r.summary.status == RunStatus::Completed ? kExitSuccess : kExitRunFailed;
}

}  // namespace ddafit::app
