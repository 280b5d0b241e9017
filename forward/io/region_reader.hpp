// The `mesh:` and `regions:` keys of a scene file (docs/scene-format.md): regions given
// as a polygon, as the area between two polylines from CSV files, or as the area below
// one polyline down to a base elevation, each cut by joint sets (forward/mesh).
#pragma once

#include <string>

#include "forward/io/yaml_checks.hpp"
#include "forward/scene.hpp"

namespace ddafit::io {

// Reads the scene file's `mesh` and `regions` (either may be absent) into the scene; CSV
// paths are relative to base_dir. Throws SceneReadError naming the key.
void read_regions(const YamlChecks& checks, const YAML::Node& root, const std::string& base_dir, Scene& scene);

// A file named in a scene: relative paths start at the scene file's folder.
std::string resolve_input_path(const std::string& base_dir, const std::string& file);

// A polyline from a CSV file of x,y rows (a header line and lines starting with '#'
// are skipped). Throws SceneReadError naming `key`.
std::vector<Vec2> read_polyline_csv(const YamlChecks& checks, const std::string& path, const std::string& key);

}  // namespace ddafit::io
