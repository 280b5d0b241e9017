// Study parameters set as numbers on a scene read once (forward/io/scene_parameter.hpp)
// must give the scene the file gives when the same value is written into its text (the
// CLI's --set, and the inversion's path before typed parameters): for every key of the
// table, valid values and refused ones alike.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "forward/io/scene_parameter.hpp"
#include "forward/io/scene_reader.hpp"

namespace ddafit::io {
namespace {

// A fixed base, a jointed region (so mesh keys cut it again), one interface given by
// percentage and one in degrees, and a control section.
const std::string kScene = R"(
time: {duration: 2.0, step: 1.0e-3}
materials:
  rock: {density: 2700, young_modulus: 5.0e9, poisson_ratio: 0.25}
interfaces:
  clay: {friction_angle: 22, degradation_percent: 20}
  joint: {friction_angle: 35, roughness_angle: 4, critical_distance_ratio: 0.02}
blocks:
  - {name: base, material: rock, fixed: true, polygon: [[-2,-2],[14,-2],[14,0],[-2,0]]}
mesh: {block_size: 2.0}
regions:
  - {name: mass, material: rock, polygon: [[0,0],[10,0],[10,4],[0,4]],
     joint_sets: [{dip: 90}, {dip: 0, spacing_ratio: 0.5}]}
contacts:
  - {between: [base, mass], interface: clay}
default_interface: joint
measure: [{name: P1, at: [5.1, 1.1]}]
output: {interval: 0.01}
control: {max_displacement_ratio: 0.004, settle_passes: 10}
)";

std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// A key of the table with NAME replaced by an entry the scene has.
std::string concrete(std::string key) {
  const size_t at = key.find("NAME");
  if (at == std::string::npos) return key;
  return key.replace(at, 4, key.rfind("materials", 0) == 0 ? "rock" : "clay");
}

std::string mesh_text(const Scene& s) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g %.17g %.17g", s.mesh.block_size, s.mesh.min_area_ratio,
                s.mesh.min_angle, s.mesh.min_edge_ratio, s.mesh.max_arrangement_edges);
  return buf;
}

struct Outcome {
  bool read = false;
  std::string scene;  // scene_to_yaml + the mesh settings (which the writer leaves out)
  std::string error;
};

// What a key needs the scene to say first: v_w is read by the velocity_weakening law only,
// the shear band's numbers by thermal_pressurization (which reads no roughness), and the
// record's scale needs a record.
Overrides setup_for(const std::string& key) {
  if (key == "interfaces.clay.weakening_velocity") return {{"interfaces.clay.law", "velocity_weakening"}};
  for (const char* band : {"band_thickness", "heat_capacity", "pressurization_factor", "thermal_diffusivity",
                           "hydraulic_diffusivity"})
    if (key == std::string("interfaces.clay.") + band)
      return {{"interfaces.clay.law", "thermal_pressurization"}, {"interfaces.clay.degradation_percent", "0"}};
  if (key == "earthquake.scale")
    return {{"earthquake.units", "m/s2"}, {"earthquake.record", "[[0, 0, 0], [0.01, 1, 0], [0.02, 0, 0]]"}};
  return {};
}

Outcome as_text(const std::string& key, double value) {
  Outcome o;
  try {
    Overrides overrides = setup_for(key);
    overrides.emplace_back(key, exact(value));
    const Scene s = parse_scene(kScene, "t", "", overrides);
    o = {true, scene_to_yaml(s) + mesh_text(s), ""};
  } catch (const SceneReadError& e) {
    o.error = e.what();
  }
  return o;
}

Outcome as_number(const Scene& base, const std::string& key, double value) {
  Outcome o;
  try {
    Scene s = base;
    set_parameters(s, {SceneParameter(base, key, "t")}, {value});
    o = {true, scene_to_yaml(s) + mesh_text(s), ""};
  } catch (const SceneReadError& e) {
    o.error = e.what();
  }
  return o;
}

TEST(SceneParameter, EveryKeyGivesTheSceneTheTextGivesOrRefusesWhatTheTextRefuses) {
  // Spread over the ranges of the table's keys: each key gets some it accepts and some it
  // refuses (negative, not whole, too large).
  const std::vector<double> values{0.0, 0.0025, 0.5, 1.2, 2.0, 3.0, 25.0, 5000.0, 1e5, -1.0, 2.5, 1e9};
  for (const std::string& pattern : settable_keys()) {
    const std::string key = concrete(pattern);
    if (key == "interfaces.clay.roughness_angle") continue;  // the one intended difference: next test
    const Scene base = parse_scene(kScene, "t", "", setup_for(key));
    int accepted = 0;
    for (double v : values) {
      const Outcome text = as_text(key, v), number = as_number(base, key, v);
      ASSERT_EQ(text.read, number.read) << key << " = " << v << "\n text: " << text.error
                                        << "\n number: " << number.error;
      if (text.read) {
        ++accepted;
        EXPECT_EQ(text.scene, number.scene) << key << " = " << v;
      } else if (text.error.find(key) != std::string::npos) {
        EXPECT_NE(number.error.find(key), std::string::npos) << key << " = " << v << ": " << number.error;
      }
    }
    EXPECT_GT(accepted, 0) << key << ": no value was accepted, so nothing was compared";
  }
}

TEST(SceneParameter, APercentageRoughnessFollowsThePeakAngleAndADegreeOneReplacesIt) {
  // i = p/100 * phi_p (scene_reader.hpp): changing phi_p of a percentage-given interface
  // moves i with it, whichever parameter is set first.
  const Scene base = parse_scene(kScene, "t");
  const SceneParameter phi(base, "interfaces.clay.friction_angle", "t");
  const SceneParameter p(base, "interfaces.clay.degradation_percent", "t");
  for (const bool phi_first : {true, false}) {
    Scene s = base;
    if (phi_first) set_parameters(s, {phi, p}, {30.0, 40.0});
    else set_parameters(s, {p, phi}, {40.0, 30.0});
    EXPECT_DOUBLE_EQ(s.interfaces[0].roughness_angle, 12.0) << "i = 40 % of 30 deg";
  }
  // A roughness in degrees replaces the percentage (the file may not give both; a study
  // parameter is the value the run uses).
  Scene s = base;
  set_parameters(s, {SceneParameter(base, "interfaces.clay.roughness_angle", "t"), phi}, {3.0, 30.0});
  EXPECT_DOUBLE_EQ(s.interfaces[0].roughness_angle, 3.0);
  EXPECT_FALSE(s.interfaces[0].degradation_percent.has_value());
}

TEST(SceneParameter, AKeyOutsideTheTableIsRefusedWithTheKeysThatCanBeSet) {
  const Scene base = parse_scene(kScene, "scene.yaml");
  const auto message = [&](const std::string& key) {
    try {
      SceneParameter(base, key, "scene.yaml");
    } catch (const SceneReadError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string unknown = message("interfaces.clay.frction_angle");
  EXPECT_EQ(unknown.rfind("scene.yaml: interfaces.clay.frction_angle: not a number a study can set", 0), 0u) << unknown;
  EXPECT_NE(unknown.find("interfaces.NAME.friction_angle"), std::string::npos) << unknown;
  EXPECT_NE(message("interfaces.sand.friction_angle").find("no interface 'sand' (it has: clay, joint)"),
            std::string::npos);
  EXPECT_NE(message("materials.granite.density").find("no material 'granite'"), std::string::npos);
  EXPECT_NE(message("control.plane_strain").find("is a switch"), std::string::npos);
  EXPECT_NE(message("time.integrator").find("not a number a study can set"), std::string::npos);
  EXPECT_EQ(message("mesh.block_size"), "(accepted)");
}

TEST(SceneParameter, ANewBlockSizeCutsTheRegionAgainAndKeepsTheExplicitBlocks) {
  const Scene base = parse_scene(kScene, "t");
  Scene s = base;
  set_parameters(s, {SceneParameter(base, "mesh.block_size", "t")}, {1.0});
  // 10 x 4 m cut by vertical joints every 1 m and horizontal ones every 0.5 m: 80 blocks,
  // after the one explicit base block.
  EXPECT_EQ(s.blocks.front().name, "base");
  EXPECT_EQ(s.blocks.size(), 81u);
  EXPECT_EQ(base.blocks.size(), 21u) << "2 m: 5 x 4 blocks";
}

}  // namespace
}  // namespace ddafit::io
