#include "forward/step/resolve_impacts.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <type_traits>
#include <vector>

#include "forward/block_groups.hpp"
#include "forward/contact/corner_paths.hpp"
#include "forward/contact/contact_law.hpp"
#include "forward/mass_matrix.hpp"

namespace ddafit {
namespace {

// Gauss-Seidel sweeps over the impact points: a block landing on two points, or a pair
// that lands on each other and on a third block, couples them. A group of blocks whose
// fastest approach is below what gravity gives in one step (a resting mass settling from
// step to step: every point of a standing brick wall closes at a few mm/s) gets
// kSettleSweeps sweeps and leaves the rest to its springs. A faster one is an impact: its
// sweeps run until no point's normal speed is off its target by more than kSpeedTolerance
// of the group's fastest approach (at most kMaxSweeps); then the points the impulses set
// closing that fast (a resting neighbour the struck block is driven into) join and the
// sweeps run again, up to kMaxRounds times. Until revision 2026-11-27.8 every group got
// eight sweeps over the points closing at the step's start: a block driven into a row of
// resting blocks met the row's contacts at their springs and came back at up to 45 % of its
// speed (tests/test_impact_depth.cpp). Converging every group as an impact made the 411-
// block wall of bench/peer run 1.8 times as long (its ~1900 settling points seldom converge).
constexpr int kSettleSweeps = 8;
constexpr int kMaxSweeps = 200;
constexpr int kMaxRounds = 16;
constexpr double kSpeedTolerance = 1e-4;
// Which impact groups mark their blocks struck (and so start slides, new_points.hpp): a
// collision, approaching faster than kCollisionSpeeds times what gravity gives in a step, and
// for kCollisionSteps steps after it the slower impacts of its blocks (a struck row that the
// striker goes on pushing). Until revision 2026-11-29.5 every group faster than |g| dt marked
// its blocks: the 1621-block standing wall's courses, settling at a few cm/s, had their bed
// joints set sliding, and the open-close iteration could not settle them (20 step cuts and
// 1897 passes in 150 steps, against none and 1200 before .28.4; bench/peer). Both limits were
// measured on the implicit free-row test (tests/test_impact_rows.cpp), whose floor must not
// take more than 10 % of the striker's momentum beyond its friction: 0.075 with these, as with
// |g| dt alone; collisions only (no steps after) 0.26; collisions beyond 10 |g| dt 0.46.
constexpr double kCollisionSpeeds = 3.0;
constexpr int kCollisionSteps = 20;

struct Impact {
  int manifold = -1, point = -1;
  double target = 0.0;         // normal speed that closes the gap at the end of the step, m/s
  double normal_mass = 0.0;    // 1 / (n W n), kg/m
  double tangent_mass = 0.0;   // 1 / (t W t)
  double normal = 0.0;         // accumulated impulses, N s/m
  double tangent = 0.0;
};

}  // namespace

int resolve_impacts(ImplicitStepContext& ctx, double dt, std::vector<char>& struck) {
  struck.assign(ctx.system.blocks.size(), 0);
  std::vector<int>& steps_left = ctx.collision_steps_left;
  steps_left.resize(ctx.system.blocks.size(), 0);
  for (int& n : steps_left) n = std::max(n - 1, 0);
  BlockSystem& s = ctx.system;
  std::vector<ContactManifold>& manifolds = ctx.contacts.manifolds;
  // Rigid inverse mass and moment of inertia about the centroid, per unit thickness.
  const auto inverse_mass = [&](int b) {
    const Block& k = s.blocks[b];
    return k.fixed ? 0.0 : 1.0 / (s.density[k.material] * k.area);
  };
  const auto inverse_inertia = [&](int b) {
    const Block& k = s.blocks[b];
    return k.fixed ? 0.0 : 1.0 / (s.density[k.material] * (k.s_xx + k.s_yy));
  };
  // Velocity at r from block b's centroid of the rigid motion that carries its momentum
  // (mass_matrix.hpp): the impulses below change only that motion.
  const auto velocity = [&](int b, const Vec2& r) -> Vec2 {
    return velocity_at(momentum_rigid_velocity(s.blocks[b]), r);
  };
  const auto rigid = [&](int b) -> Vec3 {
    return s.blocks[b].fixed ? Vec3(Vec3::Zero()) : momentum_rigid_velocity(s.blocks[b]);
  };
  const auto relative = [&](const ContactManifold& m, const ContactPoint& p) -> Vec2 {
    return velocity(m.block_b, p.rb) - velocity(m.block_a, p.ra);
  };
  const auto effective_mass = [&](const ContactManifold& m, const ContactPoint& p, const Vec2& axis) {
    return rigid_effective_mass(inverse_mass(m.block_a), inverse_inertia(m.block_a), inverse_mass(m.block_b),
                                inverse_inertia(m.block_b), p.ra, p.rb, axis);
  };
  std::vector<Impact> impacts;
  constexpr int kPoints = static_cast<int>(std::extent_v<decltype(ContactManifold::points)>);
  std::vector<char> listed(manifolds.size() * kPoints, 0);  // per manifold point: an impact already
  // Lists every point not yet listed that closes faster than `beyond` past its target;
  // returns how many.
  const auto list_closing = [&](double beyond) {
    int added = 0;
    for (int k = 0; k < static_cast<int>(manifolds.size()); ++k) {
      const ContactManifold& m = manifolds[k];
      for (int q = 0; q < m.point_count; ++q) {
        if (listed[k * kPoints + q]) continue;
        const ContactPoint& p = m.points[q];
        const double target = -std::max(p.separation, 0.0) / dt;
        if (m.normal.dot(relative(m, p)) >= target - beyond) continue;
        // Two corners that pass each other within the step meet nowhere (corner_paths.hpp).
        if (apart_corners(m, p) &&
            corners_pass(s, ctx.detection.shapes, m, p, p.separation, Vec3::Zero(), Vec3::Zero(), rigid(m.block_a),
                         rigid(m.block_b), dt, ctx.detection.settings.linear_slop))
          continue;
        const double normal_mass = effective_mass(m, p, m.normal);
        if (normal_mass <= 0.0) continue;
        impacts.push_back({k, q, target, normal_mass, effective_mass(m, p, m.tangent)});
        listed[k * kPoints + q] = 1;
        ++added;
      }
    }
    return added;
  };
  // P on block b at the point, -P on block a.
  const auto apply = [&](const ContactManifold& m, const ContactPoint& p, const Vec2& impulse) {
    Vec6& va = s.blocks[m.block_a].velocity;
    Vec6& vb = s.blocks[m.block_b].velocity;
    const double wa = inverse_mass(m.block_a), wb = inverse_mass(m.block_b);
    va[0] -= wa * impulse.x(), va[1] -= wa * impulse.y(), va[2] -= inverse_inertia(m.block_a) * cross2(p.ra, impulse);
    vb[0] += wb * impulse.x(), vb[1] += wb * impulse.y(), vb[2] += inverse_inertia(m.block_b) * cross2(p.rb, impulse);
  };
  // One Gauss-Seidel sweep over `group`; returns the largest normal-speed change, m/s.
  const auto sweep = [&](const std::vector<int>& group) {
    double worst = 0.0;
    for (const int n : group) {
      Impact& i = impacts[n];
      const ContactManifold& m = manifolds[i.manifold];
      const ContactPoint& p = m.points[i.point];
      const double vn = m.normal.dot(relative(m, p));
      const double normal = std::max(i.normal + i.normal_mass * (i.target - vn), 0.0);
      worst = std::max(worst, std::abs(normal - i.normal) / i.normal_mass);
      apply(m, p, (normal - i.normal) * m.normal);
      i.normal = normal;
      // Mohr-Coulomb (contact_law.hpp), no cohesion in an impact: |friction| <= tan(phi) x normal.
      const double cap = coulomb_cap(m.friction, i.normal, 0.0);
      const double vt = m.tangent.dot(relative(m, p));
      const double tangent = std::clamp(i.tangent - i.tangent_mass * vt, -cap, cap);
      apply(m, p, (tangent - i.tangent) * m.tangent);
      i.tangent = tangent;
    }
    return worst;
  };
  // m/s: an approach faster than gravity gives in the step is an impact.
  const double impact_speed = ctx.scene.gravity.norm() * dt;
  for (int round = 0; round < kMaxRounds; ++round) {
    const int first_new = static_cast<int>(impacts.size());
    if (list_closing(round == 0 ? 0.0 : impact_speed) == 0) break;
    // Each group of blocks the impacts join (fixed blocks join none) converges on its own, so
    // that a collision far away never changes how far the sweeps go here.
    BlockGroups joined(s.blocks.size());
    for (const Impact& i : impacts) {
      const ContactManifold& m = manifolds[i.manifold];
      if (!s.blocks[m.block_a].fixed && !s.blocks[m.block_b].fixed) joined.join(m.block_a, m.block_b);
    }
    std::map<int, std::vector<int>> groups;
    for (int n = 0; n < static_cast<int>(impacts.size()); ++n) {
      const ContactManifold& m = manifolds[impacts[n].manifold];
      groups[joined.find(s.blocks[m.block_a].fixed ? m.block_b : m.block_a)].push_back(n);
    }
    for (const auto& [key, group] : groups) {
      if (group.back() < first_new) continue;  // converged in an earlier round, nothing new
      double approach = 0.0;  // m/s, the group's fastest closing speed beyond its target
      for (const int n : group) {
        const Impact& i = impacts[n];
        const ContactManifold& m = manifolds[i.manifold];
        approach = std::max(approach, i.target - m.normal.dot(relative(m, m.points[i.point])));
      }
      if (approach <= impact_speed) {
        for (int k = 0; k < kSettleSweeps; ++k) sweep(group);
      } else {
        for (int k = 0; k < kMaxSweeps; ++k)
          if (sweep(group) <= kSpeedTolerance * approach) break;
        const bool collision = approach > kCollisionSpeeds * impact_speed;
        bool marks = collision;
        for (const int n : group) {
          const ContactManifold& m = manifolds[impacts[n].manifold];
          for (const int b : {m.block_a, m.block_b}) {
            if (s.blocks[b].fixed) continue;
            marks = marks || steps_left[b] > 0;
            if (collision) steps_left[b] = kCollisionSteps + 1;  // this step and kCollisionSteps more
          }
        }
        if (!marks) continue;
        for (const int n : group) {  // the group's free blocks (a fixed one joins no group)
          const ContactManifold& m = manifolds[impacts[n].manifold];
          for (const int b : {m.block_a, m.block_b})
            if (!s.blocks[b].fixed) struck[b] = 1;
        }
      }
    }
  }
  return static_cast<int>(impacts.size());
}

}  // namespace ddafit
