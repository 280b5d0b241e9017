// Scene files: YAML in, Scene out (and back). The physics only ever sees the Scene;
// this is the one place that knows the file format (YAML; SI units, degrees, y up):
//
//   gravity: [0, -9.81]                    # optional, this default
//   time: {duration: 2.0, step: 1.0e-3}    # both required; step = initial and largest step
//   materials:                             # required, non-empty
//     rock: {density: 2700, young_modulus: 5.0e9, poisson_ratio: 0.25}
//   interfaces:                            # only friction_angle is required
//     clay: {friction_angle: 25, cohesion: 0, tensile_strength: 0,
//            roughness_angle: 5, critical_distance_ratio: 0.01}
//     # degradation_percent: p in [0, 100] may replace roughness_angle: i = p/100 * phi_p
//   blocks:                                # required, non-empty
//     - {name: plane, group: base, material: rock, fixed: true,
//        polygon: [[0,0],[30,-15],[30,-17],[0,-2]]}
//     - {name: slider, material: rock, polygon: [...], velocity: [0,0], angular_velocity: 0}
//       # name unique; group defaults to the name; fixed defaults to false; polygon in
//       # either orientation, first vertex not repeated; angular_velocity in rad/s, CCW > 0
//   contacts:                              # interface used between two groups
//     - {between: [base, slider], interface: clay}
//   default_interface: clay                # for group pairs without a rule; optional, and
//                                          # when absent a lone interface is the default
//   measure: [{name: P1, at: [x, y]}]      # material points followed through the run
//   output: {interval: 0.01}               # s between history rows; 0 (default) = every step
//   rest_speed: 0.1                        # m/s
//   control: {max_displacement_ratio: 0.005, ...}   # SimulationOptions fields, same names
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit::io {

// A scene file that cannot be used. what() is one line, "FILE: KEY: PROBLEM", where KEY
// names the entry in YAML terms (e.g. "blocks[3].polygon") and PROBLEM says what to do.
// Control characters a file or a --set value smuggled into the message (a key named
// "a\x01", a tab-laden value) are shown as '?', so the message stays one printable line.
struct SceneReadError : std::runtime_error {
  explicit SceneReadError(const std::string& message) : std::runtime_error(one_line(message)) {}
  static std::string one_line(std::string text) {
    for (char& c : text)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return text;
  }
};

// Key-value overrides applied to the file before it is read: {"interfaces.clay.
// degradation_percent", "25"} (the CLI's --set, and the inversion's parameters).
using Overrides = std::vector<std::pair<std::string, std::string>>;

// Reads and checks a scene file (runs validate_scene()). A file may start from another
// with `base: other.yaml` and override some of its keys (maps merge key by key, other
// values replace). Throws SceneReadError.
Scene read_scene(const std::string& path, const Overrides& overrides = {});

// Same, from text; file_label is used as FILE in error messages, base_dir is where
// relative CSV paths of regions start.
Scene parse_scene(const std::string& yaml_text, const std::string& file_label, const std::string& base_dir = "",
                  const Overrides& overrides = {});

// Writes a scene in the same format; parse_scene() gives back the same numbers. Defaults
// (group = name, fixed: false, zero velocities, unchanged control options) are omitted.
// Throws std::invalid_argument when a material or interface index has no entry.
std::string scene_to_yaml(const Scene& scene);

// The keys under `control:`, one per SimulationOptions field of the same name. The reader
// and the writer share this list, so a new option needs one line here.
struct ControlKey {
  const char* name;
  std::variant<double SimulationOptions::*, int SimulationOptions::*, bool SimulationOptions::*>
      field;
};
inline constexpr ControlKey kControlKeys[] = {
    {"max_displacement_ratio", &SimulationOptions::max_displacement_ratio},
    {"penalty", &SimulationOptions::penalty},
    {"penalty_factor", &SimulationOptions::penalty_factor},
    {"shear_penalty_ratio", &SimulationOptions::shear_penalty_ratio},
    {"max_open_close_iterations", &SimulationOptions::max_open_close_iterations},
    {"step_cut_factor", &SimulationOptions::step_cut_factor},
    {"step_growth_factor", &SimulationOptions::step_growth_factor},
    {"min_step_ratio", &SimulationOptions::min_step_ratio},
    {"max_penetration_ratio", &SimulationOptions::max_penetration_ratio},
    {"penalty_raise_factor", &SimulationOptions::penalty_raise_factor},
    {"max_penalty_raises", &SimulationOptions::max_penalty_raises},
    {"contact_tolerance_ratio", &SimulationOptions::contact_tolerance_ratio},
    {"search_distance_factor", &SimulationOptions::search_distance_factor},
    {"max_pushout_speed", &SimulationOptions::max_pushout_speed},
    {"settle_passes", &SimulationOptions::settle_passes},
    {"plane_strain", &SimulationOptions::plane_strain},
    {"reuse_factorization", &SimulationOptions::reuse_factorization},
    {"update_factorization", &SimulationOptions::update_factorization},
    {"contact_hertz", &SimulationOptions::contact_hertz},
    {"contact_damping_ratio", &SimulationOptions::contact_damping_ratio},
    {"split_impulses", &SimulationOptions::split_impulses},
    {"step_by_turn", &SimulationOptions::step_by_turn},
    {"rigid_blocks", &SimulationOptions::rigid_blocks},
    {"contact_passes", &SimulationOptions::contact_passes},
    {"quiet_start_steps", &SimulationOptions::quiet_start_steps},
    {"deep_overlap_ratio", &SimulationOptions::deep_overlap_ratio},
    {"sleep_time", &SimulationOptions::sleep_time},
    {"sleep_speed", &SimulationOptions::sleep_speed},
};

}  // namespace ddafit::io
