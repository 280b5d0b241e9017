// The `water:` key of a scene file (docs/scene-format.md, "Water"): a horizontal water
// surface (`level`), a phreatic surface from a CSV file or a list of points (`table`), or
// both, and the water's `density`.
#pragma once

#include <string>

#include "forward/io/yaml_checks.hpp"
#include "forward/scene.hpp"

namespace ddafit::io {

// Reads `water` into scene.water; a CSV path is relative to base_dir. Throws
// SceneReadError naming the key.
void read_water(const YamlChecks& checks, const YAML::Node& water, const std::string& base_dir, Scene& scene);

}  // namespace ddafit::io
