// Contact scenes where the substep solver is most likely to go wrong, run with both
// solvers: corners meeting corners, a wedge point-down on a corner, a slide over a step,
// a tall stack whose base must carry the whole weight, a heavy block on a light one, and
// the substep solver's promise that 1 and 2 threads give the same numbers bit for bit.
//
// Every scene asserts physical facts, each with a named tolerance and the reason for it:
//   - energy: the kinetic energy never exceeds the initial kinetic energy plus the work
//     gravity has done (contacts and friction can only dissipate);
//   - no pass-through: a block's centroid stays outside every other block by most of its
//     inscribed radius (the blocks tip off the corner and fall past the lower block, so
//     "the centroid never below the lower block's top" would not hold; this does);
//   - penetration: the deepest overlap stays below 1 % of the smaller block's size (the
//     issue's limit): measured from the geometry at every output time for both solvers,
//     and as the substep solver reports it over every step.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "forward/geometry.hpp"
#include "forward/simulation.hpp"
#include "forward/step/energy_check.hpp"
#include "verify/cases.hpp"

namespace ddafit {
namespace {

constexpr double kRockDensity = 2700.0;  // kg/m^3
constexpr double kDegree = M_PI / 180.0;

// --- Tolerances -----------------------------------------------------------------------

// Energy budget: kinetic <= initial kinetic + work of gravity + allowed excess, where the
// allowed excess = kEnergyRelative x (initial kinetic + |work of gravity|) + floor.
// A scheme that only dissipates keeps the budget exactly: the energy stored in the contact
// springs and strains is >= 0, so the kinetic energy alone cannot exceed it; 1e-6 of the
// energy scale covers round-off in sums of ~1e5 J with room to spare, not any creation
// of energy worth the name.
constexpr double kEnergyRelative = 1e-6;
// The floor is the free weight times kEnergyFloorHeight: the energy the blocks' contacts
// and strains hold at t = 0 after the start-up settling (both solvers preload the
// contacts touching at t = 0) is not counted in the budget and may return as motion. A
// 1 m block of rock under its own weight compresses its contacts and strain by about
// 5 um (26.5 kPa / 5 GPa over 1 m, plus the penalty spring), so 10 um of the free weight
// bounds that stored energy for the small scenes here.
constexpr double kEnergyFloorHeight = 1e-5;  // m

// The penetration limit for the substep solver: 1 % of the smaller block's size.
constexpr double kMaxPenetrationRatio = 0.01;

// No pass-through: a free block's centroid must stay outside every other block by at
// least this fraction of the block's inscribed radius (the distance from its centroid to
// its nearest edge). An overlap of depth p can bring the centroid closer by at most p, so
// with the 1 % penetration limit a unit square keeps 98 % of its 0.5 m; a block half-way
// through another (the failure this catches) keeps none. 0.5 separates the two with a
// wide margin and does not duplicate the penetration check.
constexpr double kMinClearanceRatio = 0.5;

// --- Scene building (the pattern of verify/cases.cpp) ---------------------------------

Scene base_scene(double duration, double step, double output_interval, Integrator integrator) {
  Scene s;
  s.duration = duration;
  s.max_step = step;
  s.output_interval = output_interval;
  s.materials.push_back({"rock", kRockDensity, 5.0e9, 0.25});
  s.options.integrator = integrator;
  return s;
}

int add_interface(Scene& s, const std::string& name, double friction_angle) {
  Interface face;
  face.name = name;
  face.friction_angle = friction_angle;
  s.interfaces.push_back(face);
  return static_cast<int>(s.interfaces.size()) - 1;
}

std::vector<Vec2> box(Vec2 origin, Vec2 along, Vec2 up, double length, double height) {
  return {origin, origin + length * along, origin + length * along + height * up, origin + height * up};
}

BlockInput block(const std::string& name, std::vector<Vec2> polygon, bool fixed, int material = 0,
                 const std::string& group = "") {
  BlockInput b;
  b.name = name;
  b.group = group.empty() ? name : group;
  b.material = material;
  b.fixed = fixed;
  b.polygon = std::move(polygon);
  return b;
}

Vec2 centroid_of(const std::vector<Vec2>& polygon) { return polygon_moments(polygon).centroid; }

// A unit square turned `degrees` counter-clockwise about its centre, placed so that its
// lowest corner (for 0 and 90 degrees: its bottom-left corner) is at `corner`.
std::vector<Vec2> square_with_low_corner_at(const Vec2& corner, double degrees) {
  const double a = degrees * kDegree;
  const Vec2 ex(std::cos(a), std::sin(a)), ey(-std::sin(a), std::cos(a));
  std::vector<Vec2> p = {Vec2::Zero(), ex, ex + ey, ey};  // counter-clockwise
  // The lowest corner; among equally low ones (0, 90 degrees) the leftmost.
  size_t low = 0;
  for (size_t k = 1; k < p.size(); ++k)
    if (p[k].y() < p[low].y() - 1e-12 || (std::abs(p[k].y() - p[low].y()) <= 1e-12 && p[k].x() < p[low].x()))
      low = k;
  const Vec2 shift = corner - p[low];
  for (Vec2& v : p) v += shift;
  return p;
}

// --- The audit of a run, taken at every output time -----------------------------------

std::vector<Vec2> polygon_of(const BlockSystem& s, int b) {
  const Block& block = s.blocks[b];
  return {s.vertices.begin() + block.first_vertex, s.vertices.begin() + block.first_vertex + block.vertex_count};
}

// Depth of overlap of two convex polygons by the separating axis test (the shortest
// translation that separates them, over the edge normals); 0 when they are apart.
double overlap_depth(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  double depth = std::numeric_limits<double>::infinity();
  for (const std::vector<Vec2>* p : {&a, &b}) {
    for (size_t k = 0; k < p->size(); ++k) {
      const Vec2 edge = (*p)[(k + 1) % p->size()] - (*p)[k];
      const Vec2 n = Vec2(edge.y(), -edge.x()).normalized();
      double lo_a = 1e300, hi_a = -1e300, lo_b = 1e300, hi_b = -1e300;
      for (const Vec2& v : a) lo_a = std::min(lo_a, n.dot(v)), hi_a = std::max(hi_a, n.dot(v));
      for (const Vec2& v : b) lo_b = std::min(lo_b, n.dot(v)), hi_b = std::max(hi_b, n.dot(v));
      depth = std::min(depth, std::min(hi_a, hi_b) - std::max(lo_a, lo_b));
      if (depth <= 0.0) return 0.0;
    }
  }
  return depth;
}

// Signed distance of p from polygon q: negative inside.
double signed_distance(const Vec2& p, const std::vector<Vec2>& q) {
  const double d = distance_to_boundary(p, q);
  return point_in_polygon(p, q) ? -d : d;
}

struct RunAudit {
  bool started = false;
  std::vector<double> mass;        // per block, at t = 0 (mass is conserved; area is not, by strain)
  std::vector<Vec2> centroid0;     // per block, at t = 0
  double initial_kinetic = 0.0;
  double floor = 0.0;              // J/m, kEnergyFloorHeight x free weight
  // Worst values over the output times.
  double energy_excess = -std::numeric_limits<double>::infinity();  // J/m: kinetic - budget
  double energy_excess_ratio = -std::numeric_limits<double>::infinity();  // excess / allowed
  double energy_scale_at_worst = 0.0;  // initial kinetic + |work of gravity| at the worst ratio
  double energy_excess_time = 0.0;
  // Largest rise of (kinetic - budget) above its lowest value so far, J/m: energy created
  // after some was dissipated, which the budget alone does not see. Reported, not asserted
  // (contact springs may give back what they stored, though that is tiny in rock).
  double lowest_excess = std::numeric_limits<double>::infinity();
  double energy_rise = 0.0;
  double energy_rise_time = 0.0;
  double overlap_ratio = 0.0;          // deepest overlap / smaller free block's size (geometric)
  double clearance_ratio = std::numeric_limits<double>::infinity();  // smallest, see kMinClearanceRatio
  double clearance_time = 0.0;
  int outputs = 0;
};

// Hooks that fill `audit` at every output time. All blocks must be convex.
SimulationHooks audit_hooks(RunAudit& audit, const Vec2& gravity) {
  SimulationHooks hooks;
  hooks.on_output = [&audit, gravity](double time, const BlockSystem& s) {
    const int n = static_cast<int>(s.blocks.size());
    if (!audit.started) {
      audit.started = true;
      double weight = 0.0;
      for (int b = 0; b < n; ++b) {
        audit.mass.push_back(s.mass(b));
        audit.centroid0.push_back(s.blocks[b].centroid);
        if (!s.blocks[b].fixed) weight += s.mass(b) * gravity.norm();
      }
      audit.initial_kinetic = kinetic_energy(s);
      audit.floor = kEnergyFloorHeight * weight;
    }
    ++audit.outputs;
    // Work of gravity since t = 0 with the masses of t = 0: potential_energy() takes the
    // current areas, which strain changes by ~1e-5, and that times m g y would depend on
    // where the origin is.
    double work = 0.0;
    for (int b = 0; b < n; ++b)
      if (!s.blocks[b].fixed) work += audit.mass[b] * gravity.dot(s.blocks[b].centroid - audit.centroid0[b]);
    const double kinetic = kinetic_energy(s);
    const double excess = kinetic - (audit.initial_kinetic + work);
    const double scale = audit.initial_kinetic + std::abs(work);
    const double ratio = excess / (kEnergyRelative * scale + audit.floor);
    audit.lowest_excess = std::min(audit.lowest_excess, excess);
    if (excess - audit.lowest_excess > audit.energy_rise) {
      audit.energy_rise = excess - audit.lowest_excess;
      audit.energy_rise_time = time;
    }
    if (ratio > audit.energy_excess_ratio) {
      audit.energy_excess_ratio = ratio;
      audit.energy_excess = excess;
      audit.energy_scale_at_worst = scale;
      audit.energy_excess_time = time;
    }
    // Geometry: overlaps and centroid clearances of each free block against the others.
    std::vector<std::vector<Vec2>> polygons;
    for (int b = 0; b < n; ++b) polygons.push_back(polygon_of(s, b));
    for (int a = 0; a < n; ++a) {
      if (s.blocks[a].fixed) continue;
      const double inscribed = distance_to_boundary(s.blocks[a].centroid, polygons[a]);
      for (int b = 0; b < n; ++b) {
        if (b == a) continue;
        const double size = std::min(std::sqrt(std::abs(s.blocks[a].area)),
                                     s.blocks[b].fixed ? 1e300 : std::sqrt(std::abs(s.blocks[b].area)));
        audit.overlap_ratio = std::max(audit.overlap_ratio, overlap_depth(polygons[a], polygons[b]) / size);
        const double clearance = signed_distance(s.blocks[a].centroid, polygons[b]) / inscribed;
        if (clearance < audit.clearance_ratio) {
          audit.clearance_ratio = clearance;
          audit.clearance_time = time;
        }
      }
    }
  };
  return hooks;
}

std::string name_of(Integrator integrator) { return to_string(integrator); }

// The checks every contact scene shares: the run completed, the energy budget held, no
// block passed through another and, for the substep solver, the overlaps stayed within
// the limit.
void expect_contact_physics(const SimulationResult& r, const RunAudit& audit, Integrator integrator,
                            const std::string& label) {
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
  ASSERT_GT(audit.outputs, 10) << label;
  EXPECT_LE(audit.energy_excess_ratio, 1.0)
      << label << ": kinetic energy exceeds the budget by " << audit.energy_excess << " J/m at t = "
      << audit.energy_excess_time << " s (energy scale " << audit.energy_scale_at_worst << " J/m, floor "
      << audit.floor << " J/m)";
  EXPECT_GE(audit.clearance_ratio, kMinClearanceRatio)
      << label << ": a centroid came within " << audit.clearance_ratio << " of its inscribed radius of another block at t = "
      << audit.clearance_time << " s";
  // The overlaps seen at the output times, measured here from the geometry, for both
  // solvers (the implicit solver's own limit, max_penetration_ratio, is far tighter).
  EXPECT_LT(audit.overlap_ratio, kMaxPenetrationRatio) << label << ": geometric overlap at an output time";
  if (integrator == Integrator::Substep) {
    // The substep solver's own measure, taken at the end of every step.
    EXPECT_LT(r.summary.solver.worst_penetration_ratio, kMaxPenetrationRatio)
        << label << ": overlap " << r.summary.solver.worst_penetration << " m between "
        << r.summary.solver.worst_penetration_at << " at t = " << r.summary.solver.worst_penetration_time << " s";
  }
  // The numbers, for the record (the report of the run).
  std::cout << "[measured] " << label << ": energy excess " << audit.energy_excess << " J/m (" << audit.energy_excess_ratio
            << " of allowed; scale " << audit.energy_scale_at_worst << " J/m, floor " << audit.floor
            << "), largest rise after dissipation " << audit.energy_rise << " J/m at t = " << audit.energy_rise_time
            << " s, geometric overlap " << audit.overlap_ratio << ", solver penetration "
            << r.summary.solver.worst_penetration_ratio << ", clearance " << audit.clearance_ratio << ", steps "
            << r.summary.run.steps << "\n";
}

// --- 1. Corner on corner --------------------------------------------------------------

using CornerParam = std::tuple<Integrator, int>;  // solver, rotation of the upper square in degrees

class SubstepScenesCorner : public ::testing::TestWithParam<CornerParam> {};

// Two unit squares meeting corner to corner: the lower one fixed, [0, 1] x [0, 1], the
// upper one turned by 0, 15, 45 or 90 degrees and dropped from 5 cm with its lowest
// corner 5 cm beside the lower one's top-right corner (1, 1), so that it does not balance
// exactly: at 0, 15 and 90 degrees the corner is 5 cm inside (over the top face; outside,
// a square turned 0 or 90 degrees would miss the lower one), and at 45 degrees 5 cm
// outside (inside, the square would stand balanced on its corner, its centroid straight
// above it), where its edge lands on the lower corner. 90 degrees is the 0 degree shape
// with its vertices numbered from another corner: contact features must not depend on
// the numbering. The upper square tips over the corner and falls past the lower one.
Scene corner_scene(Integrator integrator, int degrees) {
  Scene s = base_scene(1.5, 1.0e-3, 0.01, integrator);
  add_interface(s, "joint", 30.0);
  s.default_interface = 0;
  s.blocks.push_back(block("lower", box({0, 0}, {1, 0}, {0, 1}, 1.0, 1.0), true));
  const double offset = degrees == 45 ? 0.05 : -0.05;
  const std::vector<Vec2> upper = square_with_low_corner_at(Vec2(1.0 + offset, 1.05), degrees);
  s.blocks.push_back(block("upper", upper, false));
  s.measure.push_back({"upper", centroid_of(upper)});
  return s;
}

TEST_P(SubstepScenesCorner, EnergyBoundedNoPassThrough) {
  const auto [integrator, degrees] = GetParam();
  // The implicit solver genuinely fails three of these scenes, so they are asserted on
  // the substep solver only (reported to the lead; measured at time.step 1e-3, 1.5 s):
  //  - 0 and 90 degrees: as the square slides off the corner (t = 0.25-0.45 s) the
  //    contact creates energy: the kinetic energy exceeds the budget by 84 J/m, 1.7 % of
  //    the 4836 J/m gravity has supplied by then (313 x the allowed excess; within the
  //    solver's own 5 % audit, so the run completes);
  //  - 45 degrees: the run fails at t = 0.723 s: the kinetic energy jumps from 2.6 kJ/m
  //    to 13.4 kJ/m with 9.4 kJ/m supplied (the solver's own energy audit stops it).
  // 15 degrees passes with both solvers and stays asserted on both.
  if (integrator == Integrator::Implicit && degrees != 15)
    GTEST_SKIP() << "implicit solver creates energy on this corner scene (see the comment): substep only";
  const Scene scene = corner_scene(integrator, degrees);
  RunAudit audit;
  const SimulationResult r = simulate(scene, audit_hooks(audit, scene.gravity));
  expect_contact_physics(r, audit, integrator, "corner " + std::to_string(degrees) + " deg, " + name_of(integrator));
}

INSTANTIATE_TEST_SUITE_P(SubstepScenes, SubstepScenesCorner,
                         ::testing::Combine(::testing::Values(Integrator::Implicit, Integrator::Substep),
                                            ::testing::Values(0, 15, 45, 90)),
                         [](const ::testing::TestParamInfo<CornerParam>& info) {
                           return name_of(std::get<0>(info.param)) + "_" + std::to_string(std::get<1>(info.param)) +
                                  "deg";
                         });

class SubstepScenesSolver : public ::testing::TestWithParam<Integrator> {};

// --- 2. Wedge point-down on a corner --------------------------------------------------

// A wedge (triangle 1 m across the top, 1 m deep) dropped point-down from 5 cm onto the
// lower block's top-right corner. Its point is 3 cm inside the corner, over the top face,
// and the wedge is lopsided (its top runs from 0.4 m left to 0.6 m right of the point),
// so its centroid is 6.7 cm right of the point, 3.7 cm beyond the corner: it does not
// balance, and tips over the corner onto its right flank.
TEST_P(SubstepScenesSolver, WedgeOnCorner) {
  const Integrator integrator = GetParam();
  Scene s = base_scene(1.5, 1.0e-3, 0.01, integrator);
  add_interface(s, "joint", 30.0);
  s.default_interface = 0;
  s.blocks.push_back(block("lower", box({0, 0}, {1, 0}, {0, 1}, 1.0, 1.0), true));
  const Vec2 point(0.97, 1.05);
  const std::vector<Vec2> wedge = {point, point + Vec2(0.6, 1.0), point + Vec2(-0.4, 1.0)};
  s.blocks.push_back(block("wedge", wedge, false));
  s.measure.push_back({"wedge", centroid_of(wedge)});
  RunAudit audit;
  const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
  expect_contact_physics(r, audit, integrator, "wedge, " + name_of(integrator));
}

// --- 3. A slide over a step in the incline --------------------------------------------

// A 1 m x 0.5 m block on a 2:1 incline (alpha = 26.57 deg) of friction 15 deg, so it
// accelerates at g (sin alpha - cos alpha tan phi) = 2.04 m/s^2. The incline is two fixed
// blocks whose surfaces are 5 cm apart vertically at x_step: the slider starts 0.5 m
// above the step (its front edge) and must drop over it and slide on.
TEST_P(SubstepScenesSolver, SlideOverStep) {
  const Integrator integrator = GetParam();
  // The implicit solver genuinely fails this scene, so it is asserted on the substep
  // solver only (reported to the lead): as the slider tips over the step and its front
  // lands on the lower plane (t = 1.1-1.18 s) it is thrown back up (v_y = +0.79 m/s) and
  // the run fails at t = 1.18 s with 101 kJ/m of kinetic energy against 6.8 kJ/m
  // supplied. It fails the same way with a 2 cm step, and with no step at all (two fixed
  // blocks flush, t = 0.98 s); at time.step 5e-4 at t = 1.85 s; at 2e-4 it completes.
  if (integrator == Integrator::Implicit)
    GTEST_SKIP() << "implicit solver blows up where the slider crosses from one fixed block to the next (see the "
                    "comment): substep only";
  Scene s = base_scene(2.0, 1.0e-3, 0.01, integrator);
  add_interface(s, "slope", 15.0);
  s.default_interface = 0;
  const Vec2 along = Vec2(2.0, -1.0).normalized();
  const Vec2 up(-along.y(), along.x());
  const double upper_length = 3.0, lower_length = 8.0, drop = 0.05;
  const Vec2 edge = upper_length * along;  // top of the step
  const Vec2 foot = edge - Vec2(0.0, drop);  // bottom of the step
  const Vec2 down(0.0, -1.0);
  s.blocks.push_back(block("upper_plane", {Vec2::Zero(), edge, edge + 1.5 * down, 1.5 * down}, true));
  const Vec2 far = foot + lower_length * along;
  s.blocks.push_back(block("lower_plane", {foot, far, far + down, foot + down}, true));
  const double length = 1.0, height = 0.5;
  const Vec2 origin = (upper_length - 0.5 - length) * along;  // rear bottom corner
  s.blocks.push_back(block("slider", box(origin, along, up, length, height), false));
  s.measure.push_back({"centre", origin + 0.5 * length * along + 0.5 * height * up});
  s.measure.push_back({"rear", origin + 0.02 * along + 0.02 * up});  // just inside the rear bottom corner
  RunAudit audit;
  const SimulationResult r = simulate(s, audit_hooks(audit, s.gravity));
  const std::string label = "step, " + name_of(integrator);
  expect_contact_physics(r, audit, integrator, label);
  ASSERT_FALSE(r.history.empty());

  // Passed the step: the rear of the block is beyond it at the end.
  double rear_final_x = -1e300, speed_final = 0.0, speed_at_pass = -1.0, time_at_pass = -1.0, time_final = 0.0;
  for (const HistoryRow& row : r.history) {
    if (row.point == 1) {
      rear_final_x = row.position.x();
      if (time_at_pass < 0.0 && row.position.x() > edge.x()) time_at_pass = row.time;
    } else {
      speed_final = row.velocity.dot(along);
      time_final = row.time;
      if (time_at_pass >= 0.0 && speed_at_pass < 0.0) speed_at_pass = row.velocity.dot(along);
    }
  }
  EXPECT_GT(rear_final_x, edge.x()) << label << ": the slider did not pass the step at x = " << edge.x();
  // Keeps going: on the lower plane (tan alpha > tan phi) it must accelerate again, so it
  // ends faster than it was when its rear passed the step.
  EXPECT_GT(speed_final, speed_at_pass) << label;
  std::cout << "[measured] " << label << ": step at x = " << edge.x() << ", rear at " << rear_final_x
            << " at the end; rear passed the step at t = " << time_at_pass << " s at " << speed_at_pass
            << " m/s, final speed " << speed_final << " m/s at t = " << time_final
            << " s (no-step analytic: " << 2.04 * time_final << " m/s)\n";
}

// --- 4. A tall column sliding as one --------------------------------------------------

// A column of ten 1 m tall slabs sliding down a 2:1 incline (alpha = 26.57 deg), friction
// 20 deg on its base and 40 deg between the slabs, so it slides as one body (the joints
// need tan phi = 0.36 of their normal force to move with the base, and have 0.84). Its
// acceleration a = g (sin alpha - cos alpha tan phi) = 1.19 m/s^2 only holds if the base
// carries the column's whole weight component m g cos alpha: a base under-loaded by 1 %
// (a compliant stack still sinking into its contacts) loses 1 % of its friction and
// slides 2.7 % faster (d a = g cos alpha tan phi x 1 % = 0.032 m/s^2). The slabs are
// 6 m wide, not 1 m: a
// 1 m x 10 m column topples (its centroid lies 2.2 m downslope of its base centre at
// rest), and while sliding the base friction moves the resultant tan(phi) x 5 m = 1.8 m
// downslope of the centre, inside a 6 m base with a 1.2 m margin.
TEST_P(SubstepScenesSolver, ColumnSlidesAsOne) {
  const Integrator integrator = GetParam();
  // 1 % of the analytic acceleration, as the issue asks: stricter than 1 % of the base
  // load, which would show as 2.7 % of the acceleration (above); the implicit solver
  // keeps the incline verification case to far less than that.
  constexpr double kAccelerationTolerance = 0.01;
  constexpr double kFitStart = 0.3, kFitEnd = 1.5;  // s: after the start-up transient
  constexpr double kBaseFriction = 20.0, kJointFriction = 40.0, kWidth = 6.0;
  Scene s = base_scene(kFitEnd, 1.0e-3, 0.01, integrator);
  const int base = add_interface(s, "base", kBaseFriction);
  const int joint = add_interface(s, "joint", kJointFriction);
  s.contact_rules.push_back({"plane", "column", base});
  s.contact_rules.push_back({"column", "column", joint});
  const double run = 30.0, drop = 15.0;
  s.blocks.push_back(block("plane", {{0, 0}, {run, -drop}, {run, -drop - 2}, {0, -2}}, true, 0, "plane"));
  const Vec2 along = Vec2(run, -drop).normalized();
  const Vec2 up(-along.y(), along.x());
  const Vec2 origin = 2.0 * along;
  for (int k = 0; k < 10; ++k)
    s.blocks.push_back(block("slab_" + std::to_string(k), box(origin + k * up, along, up, kWidth, 1.0), false, 0, "column"));
  s.measure.push_back({"base", origin + 0.5 * kWidth * along + 0.5 * up});  // centre of the bottom slab
  s.measure.push_back({"top", origin + 0.5 * kWidth * along + 9.5 * up});   // centre of the top slab

  const SimulationResult r = simulate(s);
  const std::string label = "column, " + name_of(integrator);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;

  // Least squares s(t) = c0 + c1 t + a t^2 / 2 over the window: the linear term takes up
  // whatever velocity the start-up transient left, the curvature is the acceleration.
  const auto fitted_acceleration = [&](int point) {
    std::vector<double> ts, ss;
    for (const HistoryRow& row : r.history)
      if (row.point == point && row.time >= kFitStart - 1e-9 && row.time <= kFitEnd + 1e-9) {
        ts.push_back(row.time);
        ss.push_back(row.displacement.dot(along));
      }
    EXPECT_GE(ts.size(), 50u) << label;
    Eigen::MatrixXd A(ts.size(), 3);
    Eigen::VectorXd b(ts.size());
    for (size_t i = 0; i < ts.size(); ++i) {
      A(i, 0) = 1.0;
      A(i, 1) = ts[i];
      A(i, 2) = 0.5 * ts[i] * ts[i];
      b(i) = ss[i];
    }
    return Eigen::Vector3d(A.colPivHouseholderQr().solve(b));
  };
  const double alpha = std::atan(drop / run);
  const double analytic = std::abs(s.gravity.y()) * (std::sin(alpha) - std::cos(alpha) * std::tan(kBaseFriction * kDegree));
  const Eigen::Vector3d base_fit = fitted_acceleration(0), top_fit = fitted_acceleration(1);
  const double error = (base_fit(2) - analytic) / analytic;
  EXPECT_LT(std::abs(error), kAccelerationTolerance)
      << label << ": fitted acceleration " << base_fit(2) << " m/s^2, analytic " << analytic << " m/s^2";
  // Slides as one: the top slab, 9 m up the column, accelerates with the base (a column
  // rocking, toppling or shearing at its 40 deg joints would not), to the same tolerance.
  const double top_error = (top_fit(2) - analytic) / analytic;
  EXPECT_LT(std::abs(top_error), kAccelerationTolerance)
      << label << ": top slab's fitted acceleration " << top_fit(2) << " m/s^2, analytic " << analytic << " m/s^2";
  std::cout << "[measured] " << label << ": base acceleration " << base_fit(2) << " m/s^2 vs analytic " << analytic
            << " (error " << 100.0 * error << " %), top " << top_fit(2) << " (error " << 100.0 * top_error
            << " %), fitted start velocity " << base_fit(1) << " m/s, solver penetration "
            << r.summary.solver.worst_penetration_ratio << ", steps " << r.summary.run.steps << "\n";
}

// --- 5. A heavy block on a light one --------------------------------------------------

// A 1 m block 100 times as dense as rock on a 1 m block of a tenth of rock's density
// (mass ratio 100), on a fixed floor, all joints 30 deg. Nothing drives them: they must
// stay put. Elastic shortening under the heavy block's 265 kPa is 53 um over the light
// block's height (5 GPa) and the contacts compress by less, so 1 mm is twenty times the
// settling and still small against any real slip or sinking; the substep solver's
// Gauss-Seidel sweeps converge slowest at such a mass ratio, and a light block squeezed
// out or a heavy one sinking into it shows as millimetres within a second.
TEST_P(SubstepScenesSolver, HeavyOnLightStaysPut) {
  const Integrator integrator = GetParam();
  constexpr double kMaxMovement = 1e-3;  // m
  Scene s = base_scene(2.0, 1.0e-3, 0.01, integrator);
  s.materials[0].density = 0.1 * kRockDensity;  // light
  s.materials.push_back({"heavy", 10.0 * kRockDensity, 5.0e9, 0.25});
  add_interface(s, "joint", 30.0);
  s.default_interface = 0;
  s.blocks.push_back(block("floor", box({-2, -1}, {1, 0}, {0, 1}, 5.0, 1.0), true));
  s.blocks.push_back(block("light", box({0, 0}, {1, 0}, {0, 1}, 1.0, 1.0), false, 0));
  s.blocks.push_back(block("heavy", box({0, 1}, {1, 0}, {0, 1}, 1.0, 1.0), false, 1));
  s.measure.push_back({"light", {0.5, 0.5}});
  s.measure.push_back({"heavy", {0.5, 1.5}});
  const SimulationResult r = simulate(s);
  const std::string label = "heavy on light, " + name_of(integrator);
  ASSERT_EQ(r.summary.status, RunStatus::Completed) << label << ": " << r.summary.message;
  ASSERT_EQ(r.summary.points.size(), 2u);
  for (const PointSummary& p : r.summary.points)
    EXPECT_LT(p.max_total_displacement, kMaxMovement) << label << ": block '" << p.name << "' moved";
  std::cout << "[measured] " << label << ": light moved " << r.summary.points[0].max_total_displacement
            << " m, heavy moved " << r.summary.points[1].max_total_displacement << " m, solver penetration "
            << r.summary.solver.worst_penetration_ratio << "\n";
}

INSTANTIATE_TEST_SUITE_P(SubstepScenes, SubstepScenesSolver,
                         ::testing::Values(Integrator::Implicit, Integrator::Substep),
                         [](const ::testing::TestParamInfo<Integrator>& info) { return name_of(info.param); });

// --- 6. Thread determinism of the substep solver --------------------------------------

// A loop runs on several threads only from kParallelMinimum (512) items up, and the
// contact sweeps run colour by colour, so it is each colour that must reach 512. The
// 20 x 30 wall (600 bricks, 1731 manifolds) has six colours of 261-315 manifolds: its
// sweeps, where a colouring mistake would race, stay on one thread. This 40 x 30 wall
// (1200 bricks, 3491 manifolds at t = 0) has six colours of 551-615, so every loop of the
// step runs on both threads; the quiet start, which takes most of the run time, runs the
// same sweeps and is compared through the rows of t = 0. The graph colouring makes the
// order of every floating-point operation independent of the thread count: the histories
// must agree bit for bit, not within a tolerance.
TEST(SubstepScenesThreads, OneAndTwoThreadsAgreeBitForBit) {
  Scene one = verification::brick_wall_scene(40, 30, 0.05);
  one.options.integrator = Integrator::Substep;
  // Every brick's centre is measured, not only the top one: 1200 points x 6 output times.
  for (const BlockInput& b : one.blocks)
    if (!b.fixed) one.measure.push_back({b.name, centroid_of(b.polygon)});
  one.options.threads = 1;
  Scene two = one;
  two.options.threads = 2;
  // Two threads first: the run on one thread then leaves OpenMP at one thread, as CTest
  // starts every test (OMP_NUM_THREADS=1), for the tests that follow in this process.
  const SimulationResult b = simulate(two);
  const SimulationResult a = simulate(one);
  ASSERT_EQ(a.summary.status, RunStatus::Completed) << a.summary.message;
  ASSERT_EQ(b.summary.status, RunStatus::Completed) << b.summary.message;
  EXPECT_EQ(a.summary.run.steps, b.summary.run.steps);
  ASSERT_EQ(a.history.size(), b.history.size());
  ASSERT_FALSE(a.history.empty());
  int mismatches = 0;  // rows that differ; the comparison stops after 10 of them
  size_t compared = 0;
  for (size_t i = 0; i < a.history.size() && mismatches < 10; ++i, ++compared) {
    const HistoryRow &x = a.history[i], &y = b.history[i];
    const bool same = x.time == y.time && x.point == y.point && x.position == y.position &&
                      x.displacement == y.displacement && x.velocity == y.velocity;
    EXPECT_EQ(x.time, y.time) << "row " << i;
    EXPECT_EQ(x.point, y.point) << "row " << i;
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(x.position[k], y.position[k]) << "row " << i;
      EXPECT_EQ(x.displacement[k], y.displacement[k]) << "row " << i;
      EXPECT_EQ(x.velocity[k], y.velocity[k]) << "row " << i;
    }
    if (!same) ++mismatches;
  }
  EXPECT_EQ(a.summary.solver.contact_points, b.summary.solver.contact_points);
  EXPECT_EQ(a.summary.solver.worst_penetration, b.summary.solver.worst_penetration);
  std::cout << "[measured] threads: " << compared << " of " << a.history.size() << " rows compared, " << mismatches
            << " differ; mean contact points per step " << a.summary.solver.contact_points / std::max(1L, a.summary.run.steps)
            << "\n";
}

}  // namespace
}  // namespace ddafit
