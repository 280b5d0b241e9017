// The `earthquake:` key of a scene file (docs/earthquakes.md): a ground acceleration record
// as a CSV file (columns time,ax,ay in the scene's axes), a PEER NGA `.AT2` file (one
// horizontal component in g, acting along `direction`, with an optional second `.AT2` as the
// `vertical`), or an inline list [[t, ax, ay], ...] as the writer gives it; its `units`
// (g or m/s2) and a `scale`.
#pragma once

#include <string>
#include <vector>

#include "forward/io/yaml_checks.hpp"
#include "forward/scene.hpp"

namespace ddafit::io {

// Reads `earthquake` into scene.earthquake; paths are relative to base_dir. Throws
// SceneReadError naming the key and, for a file, the line.
void read_earthquake(const YamlChecks& checks, const YAML::Node& earthquake, const std::string& base_dir,
                     Scene& scene);

// One component of a PEER NGA record (.AT2): the accelerations, in g, every `step` seconds
// from t = 0. Throws SceneReadError as "KEY: 'PATH' line N: PROBLEM".
struct At2Record {
  double step = 0.0;
  std::vector<double> acceleration;
};
At2Record read_at2(const YamlChecks& checks, const std::string& path, const std::string& key);

}  // namespace ddafit::io
