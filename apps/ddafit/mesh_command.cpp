#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "forward/io/run_files.hpp"
#include "apps/ddafit/plots.hpp"
#include "apps/ddafit/vtk_writer.hpp"
#include "forward/io/scene_reader.hpp"
#include "forward/mesh/region.hpp"

namespace ddafit::app {

int run_mesh(const MeshArgs& args) {
  Scene scene;
  if (!load_scene(args.scene, args.sets, scene)) return kExitBadInput;
  // The reader already cut the regions; cutting again gives the statistics.
  std::string problem;
  const std::vector<RegionMesh> meshes = generate_blocks(scene, problem);
  if (!problem.empty()) {
    std::cerr << args.scene << ": " << problem << "\n";
    return kExitBadInput;
  }
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  const std::filesystem::path dir(args.out);
  Scene explicit_scene = scene;
  explicit_scene.regions.clear();
  std::ofstream(dir / "scene.yaml") << "# Explicit blocks cut from " << args.scene << " by ddafit mesh\n"
                                    << io::scene_to_yaml(explicit_scene);
  write_scene_vtk((dir / "blocks.vtk").string(), scene);

  nlohmann::ordered_json j;
  j["scene"] = args.scene;
  j["block_size"] = scene.mesh.block_size;
  j["total_blocks"] = scene.blocks.size();
  std::cout << fmt::format("{:<12} {:>7} {:>10} {:>12} {:>11} {:>8} {:>11}\n", "region", "blocks", "mean size",
                           "min area", "min angle", "merged", "area error");
  for (const RegionMesh& m : meshes) {
    const MeshStats& s = m.stats;
    j["regions"][m.region] = {{"blocks", s.block_count},          {"mean_block_size", s.mean_block_size},
                              {"smallest_area", s.smallest_area}, {"smallest_angle", s.smallest_angle},
                              {"merged_slivers", s.merged_slivers}, {"remaining_slivers", s.remaining_slivers},
                              {"area_error", s.area_error},
                              {"arrangement_edges", s.arrangement_edges},
                              {"estimated_arrangement_edges", s.estimated_edges}};
    std::cout << fmt::format("{:<12} {:>7} {:>8.2f} m {:>10.2f} m2 {:>9.1f} deg {:>8} {:>11.1e}\n", m.region,
                             s.block_count, s.mean_block_size, s.smallest_area, s.smallest_angle, s.merged_slivers,
                             s.area_error);
  }
  std::ofstream(dir / "mesh.json") << j.dump(2) << "\n";
  std::string reason;
  if (!plot_blocks(args.out, scene, reason)) std::cerr << "note: blocks.png not drawn: " << reason << "\n";
  std::cout << "wrote " << (dir / "scene.yaml").string() << ", blocks.vtk, blocks.png, mesh.json\n";
  return kExitSuccess;
}

int run_plot(const PlotArgs& args) {
  Scene scene;
  if (!load_scene(args.scene, args.sets, scene)) return kExitBadInput;
  if (!std::filesystem::exists(std::filesystem::path(args.dir) / "history.csv")) {
    std::cerr << args.dir << ": no history.csv here (run ddafit simulate first)\n";
    return kExitBadInput;
  }
  // The charts pick rows by point name; a history written by another scene would be drawn
  // under the wrong labels, so the run's points must be the scene's, in the same order.
  std::ifstream history(std::filesystem::path(args.dir) / "history.csv");
  std::vector<std::string> run_points;
  std::string line, first_time;
  std::getline(history, line);  // header
  while (std::getline(history, line)) {
    const auto c1 = line.find(','), c2 = line.find(',', c1 + 1);
    if (c1 == std::string::npos || c2 == std::string::npos) break;
    if (first_time.empty()) first_time = line.substr(0, c1);
    if (line.compare(0, c1, first_time) != 0) break;
    run_points.push_back(line.substr(c1 + 1, c2 - c1 - 1));
  }
  std::vector<std::string> scene_points;
  for (const MeasurePoint& m : scene.measure) scene_points.push_back(m.name);
  if (run_points != scene_points) {
    const auto list = [](const std::vector<std::string>& v) {
      std::string s;
      for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
      return s.empty() ? std::string("none") : s;
    };
    std::cerr << args.dir << "/history.csv: its points (" << list(run_points) << ") are not the scene's measure points ("
              << list(scene_points) << "): give the scene and --set values the run used\n";
    return kExitBadInput;
  }
  for (const auto* range : {&args.observed.runout, &args.observed.peak_speed})
    if (range->size() == 2 && !((*range)[0] < (*range)[1])) {
      std::cerr << "--runout-range/--speed-range: give LOW HIGH with LOW < HIGH\n";
      return kExitBadInput;
    }
  std::string reason;
  if (!plot_history(args.dir, scene, args.scene, reason, args.observed)) {
    std::cerr << "charts not drawn: " << reason << "\n";
    return kExitRunFailed;
  }
  std::cout << "wrote distance_time.png, runout_time.png, velocity_time.png, velocity_distance.png, "
               "velocity_distance_lateral.png in " << args.dir
            << "\n";
  return kExitSuccess;
}

}  // namespace ddafit::app
