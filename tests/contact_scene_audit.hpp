// Scene builders, tolerances and the run audit (energy, pass-through, overlap) shared by
// the contact scenes of both solvers (test_substep_scenes.cpp, test_joint_crossing.cpp,
// test_toppling.cpp). Everything is in an anonymous namespace: each test file has its own.
#pragma once

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
#include "forward/run_record.hpp"
#include "forward/simulation.hpp"
#include "forward/common/energy_check.hpp"
#include "forward/water/hydrostatic.hpp"
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
// The floor is each free block's weight times a height: the energy the blocks' contacts
// and strains hold at t = 0 after the start-up settling (both solvers preload the
// contacts touching at t = 0) is not counted in the budget and may return as motion. A
// 1 m block of rock under its own weight compresses its contacts and strain by about
// 5 um (26.5 kPa / 5 GPa over 1 m, plus the penalty spring), so 10 um of the free weight
// bounds that stored energy for the small scenes here. The strain's share grows with the
// block's height H: a constant-strain block under its own weight holds A (rho g H / 2)^2 / (2 E),
// its weight times rho g H^2 / (8 E) (17 um for the 5 m blocks of tests/test_toppling.cpp, whose
// stored energy a toppling block gives back as it lifts off its rear corner); the floor takes
// the larger of the two heights (elastic_floor_height).
constexpr double kEnergyFloorHeight = 1e-5;  // m

// The floor's height for block b of `s` (above): its extent along `gravity`, H, as
// max(kEnergyFloorHeight, rho g H^2 / (8 E)), E read as the material's C_11 (E / (1 - nu^2) in plane
// stress, more in plane strain: the lower floor).
[[maybe_unused]] double elastic_floor_height(const BlockSystem& s, int b, const Vec2& gravity) {
  const Block& block = s.blocks[b];
  const double height = block_length_along(s, b, gravity.normalized()), stiffness = s.elastic[block.material](0, 0);
  return std::max(kEnergyFloorHeight, s.density[block.material] * gravity.norm() * height * height / (8.0 * stiffness));
}

// The penetration limit for the substep solver: 1 % of the smaller block's size, the
// bound past which a completed run warns (run_record.hpp).
constexpr double kMaxPenetrationRatio = kOverlapBoundRatio;

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

[[maybe_unused]] int add_interface(Scene& s, const std::string& name, double friction_angle) {
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

[[maybe_unused]] Vec2 centroid_of(const std::vector<Vec2>& polygon) { return polygon_moments(polygon).centroid; }

// A unit square turned `degrees` counter-clockwise about its centre, placed so that its
// lowest corner (for 0 and 90 degrees: its bottom-left corner) is at `corner`.
[[maybe_unused]] std::vector<Vec2> square_with_low_corner_at(const Vec2& corner, double degrees) {
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
  double initial_water = 0.0;      // J/m, the water loads' potential at t = 0 (hydrostatic.hpp)
  double floor = 0.0;              // J/m, the free weights times elastic_floor_height
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
[[maybe_unused]] SimulationHooks audit_hooks(RunAudit& audit, const Vec2& gravity) {
  SimulationHooks hooks;
  hooks.on_output = [&audit, gravity](double time, const BlockSystem& s) {
    const int n = static_cast<int>(s.blocks.size());
    if (!audit.started) {
      audit.started = true;
      for (int b = 0; b < n; ++b) {
        audit.mass.push_back(s.mass(b));
        audit.centroid0.push_back(s.blocks[b].centroid);
        if (!s.blocks[b].fixed) audit.floor += s.mass(b) * gravity.norm() * elastic_floor_height(s, b, gravity);
      }
      audit.initial_kinetic = kinetic_energy(s);
      audit.initial_water = water_potential(s, gravity.norm());
    }
    ++audit.outputs;
    // Work of gravity since t = 0 with the masses of t = 0, as the run's own audit does
    // (energy_check.hpp): the current areas change with strain by ~1e-5, and that times
    // m g y would depend on where the origin is.
    double work = 0.0;
    for (int b = 0; b < n; ++b)
      if (!s.blocks[b].fixed) work += audit.mass[b] * gravity.dot(s.blocks[b].centroid - audit.centroid0[b]);
    work += audit.initial_water - water_potential(s, gravity.norm());  // buoyancy and pore pressure: 0 when dry
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

[[maybe_unused]] std::string name_of(Integrator integrator) { return to_string(integrator); }

// The checks every contact scene shares: the run completed, the energy budget held, no
// block passed through another and, for the substep solver, the overlaps stayed within
// the limit.
[[maybe_unused]] void expect_contact_physics(const SimulationResult& r, const RunAudit& audit, Integrator integrator,
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

}  // namespace
}  // namespace ddafit
