// The scene: everything a DDA run needs, as plain data. Built by the YAML reader
// (forward/io) or in code (verification cases, benchmarks); the physics never sees YAML.
// Units are SI, angles in degrees, y points up.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "forward/options.hpp"

namespace ddafit {

using Vec2 = Eigen::Vector2d;

struct Material {
  std::string name;
  double density = 0.0;        // kg/m^3
  double young_modulus = 0.0;  // Pa
  double poisson_ratio = 0.0;  // -, in [0, 0.5)
  bool rigid = false;          // substep solver: no strain unknowns (SimulationOptions::rigid_blocks)
};

// Mohr-Coulomb interface with the bilinear roughness degradation of seed Eq. 2-3.
// What drives an interface's loss of friction from phi_p to phi_r = phi_p - i
// (forward/contact/friction_law.hpp; docs/scene-format.md, "Friction laws").
enum class FrictionLaw {
  Bilinear,           // by slip, linear over d_c: seed Eq. 2-3 (the default)
  Exponential,        // by slip, exp(-d / d_c)
  VelocityWeakening,  // by slip speed, 1 / (1 + |v| / v_w): flash heating
  ThermalPressurization,  // by the pore pressure that frictional heat raises in a shear band
};

// The law's name in a scene file ("bilinear", "exponential", "velocity_weakening",
// "thermal_pressurization").
const char* to_string(FrictionLaw law);
inline constexpr FrictionLaw kFrictionLaws[] = {FrictionLaw::Bilinear, FrictionLaw::Exponential,
                                                FrictionLaw::VelocityWeakening, FrictionLaw::ThermalPressurization};

struct Interface {
  std::string name;
  double friction_angle = 0.0;    // peak friction angle phi_p, degrees
  double cohesion = 0.0;          // Pa, lost once the contact slides or opens
  double tensile_strength = 0.0;  // Pa, lost once the contact slides or opens
  double roughness_angle = 0.0;   // i, degrees; residual angle phi_b = phi_p - i
  double critical_distance_ratio = 0.01;  // d_c / length of the overriding block
  // When the scene gives the roughness as a share of the peak angle (degradation_percent
  // p), i = p/100 * phi_p is kept in step with phi_p by whoever changes either one (the
  // reader, a study parameter); empty when roughness_angle was given.
  std::optional<double> degradation_percent;
  FrictionLaw law = FrictionLaw::Bilinear;
  double weakening_velocity = 0.1;  // v_w, m/s (velocity_weakening): half the roughness gone at v_w
  // The shear band of law: thermal_pressurization (forward/contact/laws/thermal_pressurization.hpp).
  // Defaults: Rice (2006, J. Geophys. Res. 111, B05311), representative of a fault's damaged gouge.
  double band_thickness = 1.0e-3;          // h, m
  double heat_capacity = 2.7e6;            // rho c, volumetric, J/m^3/K
  double pressurization_factor = 1.0e5;    // Lambda, Pa/K: pore pressure rise per kelvin, undrained
  double thermal_diffusivity = 7.0e-7;     // alpha_th, m^2/s
  double hydraulic_diffusivity = 4.0e-6;   // alpha_hy, m^2/s
};

// Water in the slope (forward/water/hydrostatic.hpp; docs/scene-format.md, "Water"): a
// hydrostatic pore pressure p = rho_w |g| (z_w(x) - y) wherever a block face lies below the
// water surface z_w, on every face including those in contact (joint water pressure).
struct Water {
  std::optional<double> level;  // m: a horizontal surface (a reservoir, the slope in equilibrium with it)
  std::vector<Vec2> table;      // (x, z_w) of a phreatic surface, x increasing, flat beyond its ends
  double density = 1000.0;      // rho_w, kg/m^3
  bool present() const { return level.has_value() || !table.empty(); }
};

// An earthquake's ground motion (forward/earthquake/ground_motion.hpp; docs/earthquakes.md):
// the ground's acceleration at evenly spaced times, linear between samples and zero outside
// the record. ddafit runs in the ground's frame: the fixed blocks stay put and every free
// block carries the inertial load -m scale a_g(t) at its centroid.
// How far an interval of a record may depart from its first and still count as even (relative):
// a CSV's times are rounded decimals (0.005 s written to 4 places).
inline constexpr double kEvenRecordStep = 1e-3;

struct GroundMotion {
  std::vector<double> time;        // s, strictly increasing, evenly spaced
  std::vector<Vec2> acceleration;  // m/s^2 in the scene's axes, as read (before `scale`)
  double scale = 1.0;              // multiplies the record (a study may vary it)
  bool present() const { return !time.empty(); }
};

struct BlockInput {
  std::string name;
  std::string group;  // defaults to the name
  int material = -1;  // index into Scene::materials
  bool fixed = false;
  std::vector<Vec2> polygon;  // any orientation on input; simple, non-degenerate
  Vec2 velocity = Vec2::Zero();
  double angular_velocity = 0.0;  // rad/s, counter-clockwise positive
};

// Interface used between two groups (order does not matter).
struct ContactRule {
  std::string group_a;
  std::string group_b;
  int interface = -1;  // index into Scene::interfaces
};

struct MeasurePoint {
  std::string name;
  Vec2 at = Vec2::Zero();  // a material point of the block that contains it at t = 0
};

// A family of joints. Straight: parallel lines dipping `dip` degrees below the
// horizontal towards +x (90 = vertical). Parallel: curves at constant normal distance
// above `parallel_to` (e.g. joints parallel to a basal sliding surface).
struct JointSet {
  double dip = 90.0;                // deg, straight families only
  std::vector<Vec2> parallel_to;    // polyline, ordered by increasing x; empty = straight family
  double spacing = 0.0;             // m between joints; 0 = spacing_ratio x block_size
  double spacing_ratio = 1.0;       // multiple of the region's block size
  double offset = 0.0;              // m, shifts the family along its normal
};

struct RegionInput {
  std::string name;
  std::string group;  // defaults to the name; blocks are named NAME_0001, ...
  int material = -1;
  bool fixed = false;
  std::vector<Vec2> polygon;  // simple, any orientation
  std::vector<JointSet> joint_sets;
  double block_size = 0.0;  // m; 0 = MeshSettings::block_size
};

struct MeshSettings {
  double block_size = 0.0;       // m: the one knob that scales every joint spacing
  double min_area_ratio = 0.05;  // blocks smaller than this x block_size^2 are merged
  double min_angle = 10.0;       // deg: blocks with a sharper corner are merged
  // Blocks with an edge shorter than this x block_size are merged across it. Two joints
  // crossing a third a few centimetres apart leave such edges; a vertex-edge contact on
  // one is ill-defined once a step moves a block further than the edge is long.
  double min_edge_ratio = 0.05;
  // The mesher's work bound: a region whose arrangement (outline and joint traces across its
  // bounding box) would have more edges than this is refused before it is cut. 2e6 edges
  // take about 15 s on one core; Vajont section X (6481 blocks) has 55 000.
  double max_arrangement_edges = 2.0e6;
};

struct Scene {
  Vec2 gravity = Vec2(0.0, -9.81);
  double duration = 0.0;  // s, end time
  double max_step = 0.0;  // s, initial and largest time step
  std::vector<Material> materials;
  std::vector<Interface> interfaces;
  std::vector<BlockInput> blocks;
  std::vector<ContactRule> contact_rules;
  int default_interface = -1;  // used by group pairs without a rule; -1 = none
  std::vector<MeasurePoint> measure;
  double output_interval = 0.0;  // s between history rows; 0 = every step
  double rest_speed = 0.1;       // m/s; a point slower than this is at rest
  Water water;                   // none unless the scene gives `water:`
  GroundMotion earthquake;       // none unless the scene gives `earthquake:`
  SimulationOptions options;

  // Regions to be cut into blocks (forward/mesh). Meshing appends their blocks after
  // the first explicit_block_count entries of `blocks`, so a scene can be re-meshed at
  // another block size.
  std::vector<RegionInput> regions;
  MeshSettings mesh;
  int explicit_block_count = -1;  // -1: not meshed yet, all blocks explicit
};

// A problem found in a scene: `key` names the scene entry in YAML terms
// (e.g. "blocks[3].polygon"), `problem` says what is wrong and what to do.
struct SceneError {
  std::string key;
  std::string problem;
};

// Physical and geometric checks (simple polygons, no overlaps, valid materials,
// measure points inside blocks, ...). Returns the first problem, if any.
std::vector<SceneError> validate_scene(const Scene& scene);

}  // namespace ddafit
