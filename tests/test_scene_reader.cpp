// Scene file reading: every class of bad input must give one line naming the file, the
// YAML key and the problem; good files must load with the numbers written in them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "forward/geometry.hpp"
#include "forward/io/scene_reader.hpp"

namespace ddafit::io {
namespace {

// The example from the format description. Both polygons are given clockwise.
const std::string kExample = R"(
gravity: [0, -9.81]
time: {duration: 2.0, step: 1.0e-3}
materials:
  rock: {density: 2700, young_modulus: 5.0e9, poisson_ratio: 0.25}
interfaces:
  clay: {friction_angle: 25, cohesion: 0, tensile_strength: 0, roughness_angle: 5, critical_distance_ratio: 0.01}
blocks:
  - {name: plane, group: base, material: rock, fixed: true, polygon: [[0,0],[30,-15],[30,-17],[0,-2]]}
  - {name: slider, material: rock, polygon: [[11,-3],[13,-4],[12,-6],[10,-5]], velocity: [0,0], angular_velocity: 0}
contacts:
  - {between: [base, slider], interface: clay}
default_interface: clay
measure:
  - {name: P1, at: [11.5, -4.5]}
output: {interval: 0.01}
rest_speed: 0.1
)";

const std::string kSliderPolygon = "[[11,-3],[13,-4],[12,-6],[10,-5]]";

// kExample with one piece of text replaced; the piece must exist, or the test is void.
std::string with(const std::string& from, const std::string& to, std::string text = kExample) {
  const size_t at = text.find(from);
  if (at == std::string::npos) ADD_FAILURE() << "test setup: '" << from << "' not in scene";
  else text.replace(at, from.size(), to);
  return text;
}

std::string with_slider(const std::string& polygon) { return with(kSliderPolygon, polygon); }

::testing::AssertionResult FailsWith(const std::string& yaml, const std::string& key,
                                     const std::string& word) {
  try {
    parse_scene(yaml, "test.yaml");
  } catch (const SceneReadError& e) {
    const std::string msg = e.what();
    if (msg.rfind("test.yaml: ", 0) != 0 || msg.find(key) == std::string::npos ||
        msg.find(word) == std::string::npos || msg.find('\n') != std::string::npos)
      return ::testing::AssertionFailure() << "message '" << msg << "' lacks file label, key '"
                                           << key << "' or word '" << word << "'";
    return ::testing::AssertionSuccess() << msg;
  }
  return ::testing::AssertionFailure() << "no SceneReadError";
}

// --- bad input ---------------------------------------------------------------------

TEST(SceneReader, MalformedYamlGivesLine) {
  // An unclosed flow map on line 3, noticed by the parser at the start of line 4: the
  // user needs a position, not a yaml-cpp type name.
  EXPECT_TRUE(FailsWith(with("step: 1.0e-3}", "step: 1.0e-3"), "line 4, column", "malformed"));
}

TEST(SceneReader, UnknownTopLevelKey) {
  // A misspelt or invented section must not be ignored silently.
  EXPECT_TRUE(FailsWith(kExample + "colour: red\n", "colour", "unknown key"));
}

TEST(SceneReader, UnknownNestedKey) {
  // The classic typo: without this check friction would silently be missing.
  EXPECT_TRUE(FailsWith(with("{friction_angle: 25", "{frction_angle: 25"),
                        "interfaces.clay.frction_angle", "unknown key"));
}

TEST(SceneReader, MissingTime) {
  // There is no sensible default duration or step.
  EXPECT_TRUE(FailsWith(with("time: {duration: 2.0, step: 1.0e-3}", ""), "time", "missing"));
}

TEST(SceneReader, StringForNumber) {
  // yaml-cpp's BadConversion must become a message naming the key.
  EXPECT_TRUE(FailsWith(with("density: 2700", "density: heavy"), "materials.rock.density",
                        "expected a number"));
}

TEST(SceneReader, NegativeYoungModulus) {
  // A negative stiffness makes the block matrices indefinite.
  EXPECT_TRUE(FailsWith(with("young_modulus: 5.0e9", "young_modulus: -5.0e9"),
                        "materials.rock.young_modulus", "> 0"));
}

TEST(SceneReader, PoissonRatioOfOneHalf) {
  // nu = 0.5 divides by zero in the plane strain elasticity matrix.
  EXPECT_TRUE(FailsWith(with("poisson_ratio: 0.25", "poisson_ratio: 0.5"),
                        "materials.rock.poisson_ratio", "[0, 0.5)"));
}

TEST(SceneReader, RoughnessAndDegradationBothGiven) {
  // Two ways to say the same thing; which wins would be a guess.
  EXPECT_TRUE(FailsWith(with("roughness_angle: 5", "roughness_angle: 5, degradation_percent: 20"),
                        "interfaces.clay", "not both"));
}

TEST(SceneReader, UnknownFrictionLaw) {
  // A misspelt law must not fall back to the default silently: the fit would rank the
  // wrong hypothesis.
  EXPECT_TRUE(FailsWith(with("roughness_angle: 5", "roughness_angle: 5, law: exponentail"), "interfaces.clay.law",
                        "use bilinear, exponential, velocity_weakening or thermal_pressurization"));
}

TEST(SceneReader, ShearBandNumbersWithoutTheirLawOrWithRoughness) {
  // The band of thermal_pressurization is read by that law only, and the law reads no
  // roughness: either would otherwise be ignored silently.
  EXPECT_TRUE(FailsWith(with("roughness_angle: 5", "roughness_angle: 5, band_thickness: 0.01"),
                        "interfaces.clay.band_thickness", "is read only by law: thermal_pressurization"));
  EXPECT_TRUE(FailsWith(with("roughness_angle: 5", "roughness_angle: 5, law: thermal_pressurization"),
                        "interfaces.clay.roughness_angle", "reads no roughness"));
  EXPECT_TRUE(FailsWith(with("roughness_angle: 5", "law: thermal_pressurization, heat_capacity: 0"),
                        "interfaces.clay.heat_capacity", "must be > 0"));
}

TEST(SceneReader, WeakeningVelocityWithoutItsLaw) {
  // v_w is read by velocity_weakening only; given to another law it would be ignored.
  EXPECT_TRUE(FailsWith(with("roughness_angle: 5", "roughness_angle: 5, weakening_velocity: 0.2"),
                        "interfaces.clay.weakening_velocity", "law: velocity_weakening"));
}

TEST(SceneReader, WeakeningVelocityNotPositive) {
  // mu(v) divides by v_w.
  EXPECT_TRUE(FailsWith(with("roughness_angle: 5", "roughness_angle: 5, law: velocity_weakening, weakening_velocity: 0"),
                        "interfaces.clay.weakening_velocity", "> 0"));
}

TEST(SceneReader, WaterWithoutASurface) {
  // Only a density says nothing about where the water stands.
  EXPECT_TRUE(FailsWith(kExample + "water: {density: 1000}\n", "water", "give level: Z"));
}

TEST(SceneReader, WaterTableGoingBack) {
  // z_w(x) must be a function of x.
  EXPECT_TRUE(FailsWith(kExample + "water: {table: [[0, 5], [10, 4], [10, 3]]}\n", "water.table[2]", "x must increase"));
}

TEST(SceneReader, WaterTableFileMissing) {
  EXPECT_TRUE(FailsWith(kExample + "water: {table: no_such_table.csv}\n", "water.table", "no_such_table.csv"));
}

TEST(SceneReader, WaterDensityNotPositive) {
  EXPECT_TRUE(FailsWith(kExample + "water: {level: 3, density: 0}\n", "water.density", "> 0"));
}

TEST(SceneReader, WaterUnderSidewaysGravity) {
  // The pressure's depth is measured along y.
  EXPECT_TRUE(FailsWith(with("gravity: [0, -9.81]", "gravity: [1, -9.81]") + "water: {level: 3}\n", "water", "gravity along -y"));
}

TEST(SceneReader, UnknownMaterial) {
  EXPECT_TRUE(FailsWith(with("name: slider, material: rock", "name: slider, material: granite"),
                        "blocks[1].material", "unknown material 'granite'"));
}

TEST(SceneReader, UnknownGroupInContacts) {
  // A rule for a group that no block has would never apply: almost surely a typo.
  EXPECT_TRUE(FailsWith(with("between: [base, slider]", "between: [base, slidr]"),
                        "contacts[0].between", "unknown group 'slidr'"));
}

TEST(SceneReader, PolygonWithTwoVertices) {
  EXPECT_TRUE(FailsWith(with_slider("[[11,-3],[13,-4]]"), "blocks[1].polygon", "at least 3"));
  EXPECT_TRUE(FailsWith(with_slider("[[11,-3],[13,-4]]"), "blocks[1].polygon", "'slider'"));
}

TEST(SceneReader, SelfIntersectingPolygon) {
  // A bow-tie has no well-defined inside; the message must name the crossing edges.
  EXPECT_TRUE(FailsWith(with_slider("[[10,0],[12,2],[12,0],[10,2]]"), "blocks[1].polygon",
                        "edge 0 (vertex 0 to 1) crosses edge 2 (vertex 2 to 3)"));
}

TEST(SceneReader, ZeroAreaPolygon) {
  // Collinear vertices: no mass, a singular mass matrix.
  EXPECT_TRUE(FailsWith(with_slider("[[10,0],[11,0],[12,0]]"), "blocks[1].polygon", "zero area"));
}

TEST(SceneReader, RepeatedVertex) {
  // A zero-length edge breaks contact detection.
  EXPECT_TRUE(FailsWith(with_slider("[[10,0],[11,0],[11,0],[10,1]]"), "blocks[1].polygon",
                        "vertices 1 and 2 at the same point"));
}

TEST(SceneReader, ClosingVertexRepeated) {
  // Common habit from other tools; tell the user the polygon closes itself.
  EXPECT_TRUE(FailsWith(with_slider("[[10,0],[11,0],[10,1],[10,0]]"), "blocks[1].polygon",
                        "do not repeat the first vertex"));
}

TEST(SceneReader, OverlappingBlocks) {
  // The slider moved 1 m down sits inside the plane: huge contact forces on step one.
  const std::string yaml = with_slider("[[11,-4],[13,-5],[12,-7],[10,-6]]");
  EXPECT_TRUE(FailsWith(yaml, "blocks[1].polygon", "overlaps"));
  EXPECT_TRUE(FailsWith(yaml, "blocks[1].polygon", "'slider' overlaps block 'plane'"));
}

TEST(SceneReader, MeasurePointOutsideEveryBlock) {
  // A point in the air has no block to follow.
  EXPECT_TRUE(FailsWith(with("at: [11.5, -4.5]", "at: [50, 50]"), "measure[0].at", "outside"));
}

TEST(SceneReader, DuplicateBlockNames) {
  // Names identify blocks in the output; the group keeps the contact rule valid.
  EXPECT_TRUE(FailsWith(with("name: slider,", "name: plane, group: slider,"), "blocks[1].name",
                        "unique"));
}

TEST(SceneReader, BadControlValue) {
  // A cut factor >= 1 would never shorten the step.
  EXPECT_TRUE(FailsWith(kExample + "control: {step_cut_factor: 1.5}\n", "control.step_cut_factor",
                        "(0, 1)"));
  EXPECT_TRUE(FailsWith(kExample + "control: {max_open_close_iterations: 2.5}\n",
                        "control.max_open_close_iterations", "whole number"));
  // A negative sleep speed would put no block to sleep, silently.
  EXPECT_TRUE(FailsWith(kExample + "control: {sleep_speed: -0.05}\n", "control.sleep_speed", "[0, 1000]"));
  // A deep overlap of a fifth of a block would leave blocks pressed through each other uncorrected.
  EXPECT_TRUE(FailsWith(kExample + "control: {deep_overlap_ratio: 0.2}\n", "control.deep_overlap_ratio", "[0, 0.1]"));
  EXPECT_TRUE(FailsWith(kExample + "control: {deep_overlap_ratio: -1e-3}\n", "control.deep_overlap_ratio", "[0, 0.1]"));
  // A quiet start of negative or fractional length has no meaning; one of a million steps would
  // run for hours before t = 0.
  EXPECT_TRUE(FailsWith(kExample + "control: {quiet_start_steps: -1}\n", "control.quiet_start_steps", "[0, 10000]"));
  EXPECT_TRUE(FailsWith(kExample + "control: {quiet_start_steps: 2.5}\n", "control.quiet_start_steps", "whole number"));
  EXPECT_TRUE(FailsWith(kExample + "control: {quiet_start_steps: 1000000}\n", "control.quiet_start_steps", "[0, 10000]"));
}

TEST(SceneReader, UnreadableFile) {
  try {
    read_scene("/nonexistent/scene.yaml");
    FAIL() << "no SceneReadError";
  } catch (const SceneReadError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.yaml: cannot read"),
              std::string::npos)
        << e.what();
  }
}

// --- good input --------------------------------------------------------------------

TEST(SceneReader, ExampleLoads) {
  const Scene s = parse_scene(kExample, "example.yaml");
  EXPECT_EQ(s.gravity, Vec2(0, -9.81));
  EXPECT_EQ(s.duration, 2.0);
  EXPECT_EQ(s.max_step, 1.0e-3);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "rock");
  EXPECT_EQ(s.materials[0].density, 2700);
  EXPECT_EQ(s.materials[0].young_modulus, 5.0e9);
  EXPECT_EQ(s.materials[0].poisson_ratio, 0.25);
  ASSERT_EQ(s.interfaces.size(), 1u);
  EXPECT_EQ(s.interfaces[0].friction_angle, 25);
  EXPECT_EQ(s.interfaces[0].roughness_angle, 5);
  EXPECT_EQ(s.interfaces[0].critical_distance_ratio, 0.01);
  ASSERT_EQ(s.blocks.size(), 2u);
  EXPECT_EQ(s.blocks[0].group, "base");
  EXPECT_TRUE(s.blocks[0].fixed);
  EXPECT_EQ(s.blocks[1].group, "slider");  // defaults to the name
  EXPECT_FALSE(s.blocks[1].fixed);
  EXPECT_EQ(s.blocks[1].material, 0);
  // Clockwise input is accepted and kept as given; orientation is the physics' business.
  ASSERT_EQ(s.blocks[1].polygon.size(), 4u);
  EXPECT_EQ(s.blocks[1].polygon[0], Vec2(11, -3));
  EXPECT_LT(signed_area(s.blocks[0].polygon), 0.0);
  EXPECT_LT(signed_area(s.blocks[1].polygon), 0.0);
  ASSERT_EQ(s.contact_rules.size(), 1u);
  EXPECT_EQ(s.contact_rules[0].group_a, "base");
  EXPECT_EQ(s.contact_rules[0].group_b, "slider");
  EXPECT_EQ(s.contact_rules[0].interface, 0);
  EXPECT_EQ(s.default_interface, 0);
  ASSERT_EQ(s.measure.size(), 1u);
  EXPECT_EQ(s.measure[0].at, Vec2(11.5, -4.5));
  EXPECT_EQ(s.output_interval, 0.01);
  EXPECT_EQ(s.rest_speed, 0.1);
  EXPECT_EQ(s.options.step_cut_factor, SimulationOptions{}.step_cut_factor);
}

TEST(SceneReader, LoneInterfaceIsTheDefault) {
  // Documented shortcut: with one interface and no default_interface, use it everywhere.
  EXPECT_EQ(parse_scene(with("default_interface: clay\n", ""), "t").default_interface, 0);
}

TEST(SceneReader, DegradationPercentSetsRoughness) {
  // i = p/100 * phi_p: 25 % of 40 degrees.
  const Scene s = parse_scene(
      with("clay: {friction_angle: 25, cohesion: 0, tensile_strength: 0, roughness_angle: 5,",
           "clay: {friction_angle: 40, degradation_percent: 25,"),
      "t");
  EXPECT_DOUBLE_EQ(s.interfaces[0].roughness_angle, 10.0);
}

TEST(SceneReader, WrittenSceneReadsBackExactly) {
  // The mesh generator writes scenes with scene_to_yaml; nothing may drift on the way.
  Scene s = parse_scene(kExample, "t");
  s.gravity = Vec2(0.1, -9.80665);
  s.interfaces.push_back({"joint", 1.0 / 3.0, 1e5, 2.5e4, 0.2, 0.05, std::nullopt, FrictionLaw::VelocityWeakening, 0.3});
  s.gravity = Vec2(0.0, -9.80665);  // water needs gravity along -y
  s.water.level = 1.0 / 3.0;
  s.water.table = {{-1.5, 2.0 / 3.0}, {4.0, 1e-7}};
  s.water.density = 1025.0;
  s.contact_rules[0].interface = 1;
  s.blocks[1].velocity = Vec2(1.0 / 7.0, -2e-300);
  s.blocks[1].angular_velocity = -0.3;
  s.blocks[1].polygon[0] = Vec2(11 + 1e-13, -3);
  s.measure.push_back({"P2", Vec2(20, -11)});
  s.options.penalty = 7.5e10;
  s.options.max_penalty_raises = 3;
  s.options.plane_strain = false;

  const Scene r = parse_scene(scene_to_yaml(s), "written.yaml");
  EXPECT_EQ(r.gravity, s.gravity);
  EXPECT_EQ(r.duration, s.duration);
  EXPECT_EQ(r.max_step, s.max_step);
  ASSERT_EQ(r.materials.size(), s.materials.size());
  EXPECT_EQ(r.materials[0].name, s.materials[0].name);
  EXPECT_EQ(r.materials[0].young_modulus, s.materials[0].young_modulus);
  ASSERT_EQ(r.interfaces.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(r.interfaces[k].name, s.interfaces[k].name);
    EXPECT_EQ(r.interfaces[k].friction_angle, s.interfaces[k].friction_angle);
    EXPECT_EQ(r.interfaces[k].cohesion, s.interfaces[k].cohesion);
    EXPECT_EQ(r.interfaces[k].tensile_strength, s.interfaces[k].tensile_strength);
    EXPECT_EQ(r.interfaces[k].roughness_angle, s.interfaces[k].roughness_angle);
    EXPECT_EQ(r.interfaces[k].critical_distance_ratio, s.interfaces[k].critical_distance_ratio);
    EXPECT_EQ(r.interfaces[k].law, s.interfaces[k].law);
    EXPECT_EQ(r.water.level, s.water.level);
    EXPECT_EQ(r.water.table, s.water.table);
    EXPECT_EQ(r.water.density, s.water.density);
    EXPECT_EQ(r.interfaces[k].weakening_velocity, s.interfaces[k].weakening_velocity);
  }
  ASSERT_EQ(r.blocks.size(), s.blocks.size());
  for (size_t k = 0; k < s.blocks.size(); ++k) {
    EXPECT_EQ(r.blocks[k].name, s.blocks[k].name);
    EXPECT_EQ(r.blocks[k].group, s.blocks[k].group);
    EXPECT_EQ(r.blocks[k].material, s.blocks[k].material);
    EXPECT_EQ(r.blocks[k].fixed, s.blocks[k].fixed);
    EXPECT_EQ(r.blocks[k].polygon, s.blocks[k].polygon);
    EXPECT_EQ(r.blocks[k].velocity, s.blocks[k].velocity);
    EXPECT_EQ(r.blocks[k].angular_velocity, s.blocks[k].angular_velocity);
  }
  ASSERT_EQ(r.contact_rules.size(), 1u);
  EXPECT_EQ(r.contact_rules[0].group_a, "base");
  EXPECT_EQ(r.contact_rules[0].interface, 1);
  EXPECT_EQ(r.default_interface, s.default_interface);
  ASSERT_EQ(r.measure.size(), 2u);
  EXPECT_EQ(r.measure[1].name, "P2");
  EXPECT_EQ(r.measure[1].at, s.measure[1].at);
  EXPECT_EQ(r.output_interval, s.output_interval);
  EXPECT_EQ(r.rest_speed, s.rest_speed);
  EXPECT_EQ(r.options.penalty, s.options.penalty);
  EXPECT_EQ(r.options.max_penalty_raises, 3);
  EXPECT_FALSE(r.options.plane_strain);
}

TEST(ValidateScene, LargeMeshOfTouchingBlocks) {
  // 10^4 unit squares sharing edges: touching is legal, and the overlap search must not
  // test all 5e7 pairs. One shifted block must still be caught.
  Scene s = parse_scene(kExample, "t");
  s.blocks.clear();
  s.contact_rules.clear();
  s.measure = {{"P", Vec2(0.5, 0.5)}};
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) {
      BlockInput b;
      b.name = std::string("b").append(std::to_string(i)).append("_").append(std::to_string(j));
      b.group = b.name;
      b.material = 0;
      b.fixed = j == 0;
      b.polygon = {Vec2(i, j), Vec2(i + 1, j), Vec2(i + 1, j + 1), Vec2(i, j + 1)};
      s.blocks.push_back(b);
    }
  EXPECT_TRUE(validate_scene(s).empty());

  for (Vec2& p : s.blocks[5050].polygon) p += Vec2(0.3, 0.2);
  const std::vector<SceneError> errors = validate_scene(s);
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].problem.find("overlaps"), std::string::npos) << errors[0].problem;
}

// Two equal-height blocks shifted along their shared top and bottom lines: every
// vertex lies on the other's boundary and no edges cross properly, yet they overlap.
TEST(ValidateScene, OverlapAlongSharedLines) {
  const std::vector<Vec2> a{{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const std::vector<Vec2> b{{1, 0}, {3, 0}, {3, 1}, {1, 1}};
  EXPECT_TRUE(polygons_overlap(a, b, 1e-6));
}

}  // namespace
}  // namespace ddafit::io
