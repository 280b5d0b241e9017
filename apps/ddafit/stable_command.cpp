#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>

#include "apps/ddafit/commands.hpp"
#include "apps/ddafit/exit_codes.hpp"
#include "forward/io/run_files.hpp"
#include "forward/analysis/stable_friction.hpp"
#include "forward/io/scene_reader.hpp"

namespace ddafit::app {

int run_stable(const StableArgs& args) {
  Scene scene;
  if (!load_scene(args.scene, args.sets, scene)) return kExitBadInput;
  StableSearchOptions o = args.options;
  for (size_t k = 0; k < scene.interfaces.size(); ++k)
    if (scene.interfaces[k].name == args.interface) o.interface = static_cast<int>(k);
  if (o.interface < 0) {
    std::cerr << args.scene << ": --interface: no interface '" << args.interface << "' in the scene\n";
    return kExitBadInput;
  }
  if (!(o.low < o.high) || !(o.tolerance > 0.0) || !(o.trial_duration > 0.0) || !(o.max_movement >= 0.0)) {
    std::cerr << "ddafit stable: need --low < --high and positive --tolerance, --time and --movement\n";
    return kExitBadInput;
  }
  if (const std::string problem = io::prepare_output_folder(args.out); !problem.empty()) {
    std::cerr << problem << "\n";
    return kExitBadInput;
  }
  std::cout << fmt::format("a trial is stable when, over its last {} s, every measure point is slower than {} m/s "
                           "(rest_speed) and the speeds are not rising{}\n",
                           o.rest_window, scene.rest_speed,
                           o.max_movement > 0.0 ? fmt::format(", and no point moved more than {} m", o.max_movement)
                                                : std::string());
  std::cout << fmt::format("{:>10} {:>14} {:>18} {:>8} {:>8}\n", "phi (deg)", "movement (m)", "window speed (m/s)",
                           "rising", "stable");
  const StableSearchResult r = find_stable_friction(scene, o, [](const StableTrial& t) {
    std::cout << fmt::format("{:>10.3f} {:>14.4f} {:>18.4f} {:>8} {:>8}{}\n", t.friction_angle, t.movement,
                             t.window_speed, t.rising ? "yes" : "no", t.stable ? "yes" : "no",
                             t.failure.empty() ? "" : "  (run failed: " + t.failure + ")")
              << std::flush;
  });
  const std::string json_path = (std::filesystem::path(args.out) / "stable.json").string();
  try {
    io::write_stable_json(json_path, {args.scene, args.interface, scene.rest_speed, o}, r);
  } catch (const std::runtime_error&) {
    std::cerr << json_path << ": --out: cannot write the file\n";
    return kExitBadInput;
  }
  if (!r.bracketed) {
    std::cerr << args.scene << ": stable search: " << r.message << "\n";
    return kExitRunFailed;
  }
  std::cout << fmt::format("stable for {} friction angle between {:.3f} and {:.3f} deg\n", args.interface, r.low,
                           r.high);
  return kExitSuccess;
}

}  // namespace ddafit::app
