// The numbers of a read scene that a study parameter may set, named by their key in
// scene-file terms, and the one table that lists them (scene_parameter.cpp). A study's
// scene is read once; each point of the study copies it and sets its parameters here,
// as numbers, instead of writing them into the file's text and reading the file again.
//
//   time.duration, time.step, time.substeps, output.interval, rest_speed
//   materials.NAME.{density, young_modulus, poisson_ratio}
//   interfaces.NAME.{friction_angle, cohesion, tensile_strength, roughness_angle,
//                    degradation_percent, critical_distance_ratio, weakening_velocity,
//                    band_thickness, heat_capacity, pressurization_factor, thermal_diffusivity,
//                    hydraulic_diffusivity}
//   earthquake.scale
//   mesh.{block_size, min_area_ratio, min_angle, min_edge_ratio, max_arrangement_edges}
//   control.NAME, for every number of kControlKeys (switches are settings, not parameters)
#pragma once

#include <string>
#include <vector>

#include "forward/scene.hpp"

namespace ddafit::io {

class SceneParameter {
 public:
  // Resolves `key` against `scene`, read from `file`. Throws SceneReadError
  // "FILE: KEY: PROBLEM" for a key outside the table (the problem lists the keys that can
  // be set) or a material or interface the scene does not define.
  SceneParameter(const Scene& scene, const std::string& key, const std::string& file);

  const std::string& key() const { return key_; }
  const std::string& file_label() const { return file_; }
  // The mesh keys: the scene's regions are cut into blocks again after one is set.
  bool recuts_blocks() const;
  // Sets the number. Throws SceneReadError when this key cannot take it (a whole number
  // expected, a percentage outside [0, 100]); the scene as a whole is checked by
  // set_parameters().
  void set(Scene& scene, double value) const;

 private:
  int row_ = -1;      // into the table; kControlRow for a key under control:
  int control_ = -1;  // into kControlKeys
  int entry_ = -1;    // the named material or interface
  std::string key_, file_;
};

// Sets each parameter to its value, cuts the regions into blocks again when a mesh key is
// among them, and checks the scene as the reader does (validate_scene). Throws
// SceneReadError "FILE: KEY: PROBLEM".
void set_parameters(Scene& scene, const std::vector<SceneParameter>& parameters, const std::vector<double>& values);

// Every key the table accepts, with NAME standing for a material or interface name:
// for messages and the docs.
std::vector<std::string> settable_keys();

}  // namespace ddafit::io
