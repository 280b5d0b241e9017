// The inversion's one view of the forward model: a scene file and overrides in, a
// summary (and history) out. Nothing here throws: a scene that cannot be read or a run
// that fails comes back as a SimulationResult with a status and a message.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "forward/simulation.hpp"
#include "inverse/study.hpp"

namespace ddafit::inverse {

using Overrides = std::vector<std::pair<std::string, std::string>>;

// read_scene(path, overrides) + simulate(). Tests may substitute their own.
using ForwardModel = std::function<SimulationResult(const std::string& scene_path, const Overrides& overrides)>;

SimulationResult run_forward(const std::string& scene_path, const Overrides& overrides);

// A value as an override string that reads back as the same double (17 digits).
std::string exact_text(double value);

// The overrides for one point: the study's fixed settings, then one per parameter.
Overrides point_overrides(const Study& study, const std::vector<double>& values);

// FNV-1a 64-bit hash, hex, of everything the scene reader reads for this study: the scene
// file, its `base:` chain, every file a scene names that exists next to it (CSV surfaces),
// and the study's fixed settings. Changing any of these starts a new cache key.
std::string scene_input_hash(const Study& study);

// Peak friction angle (deg) of the interface a key "interfaces.NAME.*" belongs to, read
// from the scene at the given point; NaN when the key names no interface.
double peak_friction_angle(const Study& study, const std::vector<double>& values, const std::string& key);

}  // namespace ddafit::inverse
