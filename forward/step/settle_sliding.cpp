#include "forward/step/settle_sliding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "forward/common/displace_block.hpp"
#include "forward/contact/contact_law.hpp"
#include "forward/step/held_groups.hpp"
#include "forward/step/settle_contacts.hpp"
#include "forward/step/sliding_groups.hpp"

namespace ddafit {
namespace {

// The passes stop once a pass moves no block by more than this share of the first pass's
// largest move. Not settle_contacts' share of max_shift: that scales with the model (2.5 mm
// for a 200 m block on a 10 km plane, where the start then ran 1.5 % off seed Eq. 4).
constexpr double kSlidingTolerance = 1e-3;

// The passes' step, as a multiple of settle_contacts' (itself kSettleStepScale times the run's):
// the blocks' inertia, 2 M / dt^2, only slows the passes down here, since d'Alembert's loads
// balance each group along its slip. At settle_contacts' step a 200 x 50 m frictionless slab
// took 28 passes (its strain moving by a fifth less each pass); at ten times it, 4.
constexpr double kSlidingStepScale = 10.0;

// The deepest overlap of any closed point, m.
double deepest_overlap(const ContactSet& contacts) {
  double deepest = 0.0;
  for (const ContactManifold& m : contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q)
      if (m.points[q].spring.state != ContactState::Open) deepest = std::max(deepest, -m.points[q].separation);
  return deepest;
}

// Sets m's closed points carrying more than `loaded` sliding at their caps, block b of the manifold
// slipping along `direction` against the other.
void slide_loaded_points(const BlockSystem& s, ContactManifold& m, int b, const Vec2& direction, double loaded,
                         const StepParameters& step) {
  for (int q = 0; q < m.point_count; ++q) {
    ContactPoint& p = m.points[q];
    SpringState& c = p.spring;
    if (c.state == ContactState::Open || c.normal_force <= loaded) continue;
    c.state = ContactState::Sliding;
    c.slip_direction = side(m, b) * (direction.dot(m.tangent) > 0.0 ? 1.0 : -1.0);
    c.shear_offset = sliding_shear_offset(s.interfaces[m.interface], m, p, step.shear_penalty);
  }
}

// Every loaded point between a sliding group and a block outside it, on a face parallel to the
// group's slip, slides with it at its cap: a point the settling left locked under its cap (the
// less loaded corner of a block, or one found again by the detection) would otherwise hold the
// block back in its first step and set it turning.
void slide_whole_faces(const BlockSystem& s, ContactSet& contacts, const SlidingGroups& g, const StepParameters& step) {
  const double largest = largest_normal_force(contacts);
  for (ContactManifold& m : contacts.manifolds) {
    for (const int b : {m.block_a, m.block_b}) {
      const int k = g.group[b];
      const int other = b == m.block_a ? m.block_b : m.block_a;
      if (k < 0 || g.group[other] == k || g.tangent[k].isZero()) continue;
      // Only the faces its slip was read from: the lower block of a weaker joint slides down its
      // face, and the joint above it is the upper block's to set.
      if ((g.group[other] < 0) != static_cast<bool>(g.on_ground[k])) continue;
      const Vec2& t = g.tangent[k];
      if (!parallel(t, m.tangent)) continue;
      slide_loaded_points(s, m, b, t, kLoadedShare * largest, step);
    }
  }
}

// A group resting on one face whose weight along it exceeds the sum of that face's caps slides,
// though settle_contacts may have stopped before any point's locked shear passed its own cap: its
// tolerance scales with the model (2.5 mm of move per pass on a plane 10 km long, where a 100 m
// stack started held, and its upper block ran 22 % off seed Eq. 4). Such a group's points on the
// face are set sliding down it, at their caps. So is a group whose points load_springs set sliding
// both ways along the face (sliding_groups reads that as a block at rest whose corners spread):
// locked, a block tall for its base turns forward on its springs and its rear corner's shear points
// up the face. Read as at rest, a 3 x 7 m block 1 deg steeper than its friction started from the
// locked state and ran 3 % ahead of seed Eq. 4 at its first centimetre (the kick of Known limits
// (i)); set sliding down, the passes below settle it as it slides and it runs within 1e-5
// (model revision 2026-12-06.15).
void slide_overloaded_groups(const BlockSystem& s, ContactSet& contacts, const std::vector<char>& settled,
                             const std::vector<Vec6>& velocities, const StepParameters& step) {
  const SlidingGroups g = sliding_groups(s, contacts, settled, {});
  const size_t groups = g.tangent.size();
  const double largest = largest_normal_force(contacts);
  std::vector<Vec2> face(groups, Vec2::Zero());
  std::vector<double> capacity(groups, 0.0), demand(groups, 0.0);
  std::vector<char> skip(groups, 0);
  for (const ContactManifold& m : contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q) {
      const ContactPoint& p = m.points[q];
      if (p.spring.state == ContactState::Open || p.spring.normal_force <= kLoadedShare * largest) continue;
      for (const int b : {m.block_a, m.block_b}) {
        const int k = g.group[b];
        const int other = b == m.block_a ? m.block_b : m.block_a;
        if (k < 0 || g.group[other] == k) continue;
        // Sliding already, the passes see it; unless its points slip both ways along the face and
        // sliding_groups gave it no slip.
        if (p.spring.state == ContactState::Sliding && !g.tangent[k].isZero()) skip[k] = 1;
        if (face[k].isZero()) face[k] = m.tangent;
        else if (!parallel(face[k], m.tangent)) skip[k] = 1;
        capacity[k] += coulomb_cap(m.friction, p.spring.normal_force, cohesive_strength(s.interfaces[m.interface], p));
      }
    }
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const int k = g.group[b];
    if (k < 0) continue;
    if (velocities[b].head<3>().norm() != 0.0) skip[k] = 1;
    demand[k] += s.mass(b) * std::abs(face[k].dot(step.gravity));
  }
  for (ContactManifold& m : contacts.manifolds)
    for (const int b : {m.block_a, m.block_b}) {
      const int k = g.group[b];
      const int other = b == m.block_a ? m.block_b : m.block_a;
      if (k < 0 || g.group[other] == k || skip[k] || face[k].isZero() || demand[k] <= capacity[k]) continue;
      const Vec2 down = face[k].dot(step.gravity) > 0.0 ? face[k] : Vec2(-face[k]);
      slide_loaded_points(s, m, b, down, kLoadedShare * largest, step);
    }
}

// d'Alembert's load on each block of a sliding group: -m_i a t, a the group's net force along
// its slip t over its mass (net_force_along). Each group takes its own: the blocks of a weaker
// joint slide apart. Returns false, and adds nothing, if a group is given a velocity: this stage
// settles blocks that start sliding from rest. (Tried on blocks given a velocity too, it changed
// what a row struck by a square block sliding at its tipping limit, friction 45 deg, does:
// rebounds of 13 % of the impact speed, over the 11 % of tests/test_impact_rows.cpp, with the
// blocks listed in reverse.)
bool add_inertial_loads(const BlockSystem& s, const SlidingGroups& g, const std::vector<Vec6>& velocities,
                        Eigen::VectorXd& f) {
  const std::vector<double> along = net_force_along(s, g, f);
  std::vector<double> mass(along.size(), 0.0);
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const int k = g.group[b];
    if (k < 0 || g.tangent[k].isZero()) continue;
    if (velocities[b].head<3>().norm() != 0.0) return false;
    mass[k] += s.mass(b);
  }
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const int k = g.group[b];
    if (k < 0 || g.tangent[k].isZero()) continue;
    f.segment<2>(6 * s.blocks[b].unknown) -= s.mass(b) * (along[k] / mass[k]) * g.tangent[k];
  }
  return true;
}

}  // namespace

int settle_sliding_groups(ImplicitStepContext& ctx, const StepParameters& relaxed, const StepParameters& step,
                          const std::vector<char>& settled, double max_shift) {
  BlockSystem& s = ctx.system;
  std::vector<Vec6> velocities(s.blocks.size());
  for (size_t b = 0; b < s.blocks.size(); ++b) velocities[b] = s.blocks[b].velocity;
  // What a failed attempt goes back to.
  const ContactSet contacts = ctx.contacts;
  slide_overloaded_groups(s, ctx.contacts, settled, velocities, step);
  if (!sliding_groups(s, ctx.contacts, settled, {}).any) {
    ctx.contacts = contacts;
    return 0;
  }
  const std::vector<Block> blocks = s.blocks;
  const std::vector<Vec2> vertices = s.vertices;
  const std::vector<MaterialPoint> points = s.points;
  const auto restore = [&] { s.blocks = blocks, s.vertices = vertices, s.points = points, ctx.contacts = contacts; };
  const auto set_velocities = [&](bool given) {
    for (size_t b = 0; b < s.blocks.size(); ++b) s.blocks[b].velocity = given ? velocities[b] : Vec6::Zero();
  };
  GlobalSystem eq;
  StepParameters quasi = relaxed;
  quasi.time_step *= kSlidingStepScale;
  int pass = 0;
  double first = 0.0;  // the first pass's largest move
  std::vector<char> held(s.blocks.size(), 0);
  // Each stop holds a group or joins two, so there are fewer than the blocks.
  int stops = 0;
  while (pass < ctx.options.settle_passes) {
    const SlidingGroups g = sliding_groups(s, ctx.contacts, settled, held);
    if (!g.resolved) {
      restore();
      return 0;
    }
    // Held groups still settle, their points locked at the force they carried (their caps): left
    // as the first settling had them, a block whose rear corner passed its cap there started with
    // that corner sliding and the block out of balance, and crept (18 of tests/test_held_blocks.cpp's
    // 144 more than 1e-4 of their length until model revision 2026-12-06.11).
    if (!g.any && stops == 0) break;
    slide_whole_faces(s, ctx.contacts, g, step);
    set_velocities(false);  // a static pass: no inertia carried in
    assemble(s, ctx.contacts, quasi, eq);
    if (hold_stopped_groups(s, g, velocities, eq.f, ctx.contacts, held) && ++stops < static_cast<int>(s.blocks.size()))
      continue;
    ++pass;
    if (!add_inertial_loads(s, g, velocities, eq.f)) {  // a group given a velocity: left as given
      restore();
      return 0;
    }
    std::string reason;
    if (!ctx.solver.solve(eq.k, eq.f, eq.d, reason)) {
      restore();
      return 0;
    }
    // Only the settled blocks move (a block in flight is left as given, as in settle_contacts).
    double largest = 0.0;
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
      if (s.blocks[b].unknown >= 0 && settled[b])
        largest = std::max(largest, block_displacement(s, b, eq.d.segment<6>(6 * s.blocks[b].unknown)));
    if (largest > max_shift) {
      restore();
      return 0;
    }
    // New and closing points lock where they are, as in settle_contacts' passes.
    const std::string problem = apply_settling_pass(ctx, eq.d, settled);
    if (!problem.empty()) {
      restore();
      return 0;
    }
    for (ContactManifold& m : ctx.contacts.manifolds)
      for (int q = 0; q < m.point_count; ++q) {
        ContactPoint& p = m.points[q];
        if (p.spring.state == ContactState::Open && p.separation <= ctx.detection.settings.linear_slop) {
          p.spring.state = ContactState::Locked;
          p.spring.shear_offset = 0.0;
        }
      }
    set_velocities(true);  // load_springs reads them: blocks given a velocity slide from the start
    load_springs(s, ctx.contacts, step);
    // Springs far too soft for the blocks (a penalty of 1000 N/m under a 12 t/m slider) let a
    // group sink pass after pass: such a settling is not kept, and the run's penetration check
    // says what to change (forward/step/judge_step.cpp).
    if (deepest_overlap(ctx.contacts) > ctx.control.max_penetration) {
      restore();
      return 0;
    }
    if (pass == 1) first = largest;
    if (largest <= kSlidingTolerance * first) break;
  }
  // No group slides or is held after all, or a hold friction cannot give: the settled state as it was.
  if (pass == 0 || (stops > 0 && !holds_within_caps(s, ctx.contacts, settled, held, step.gravity,
                                                    step.shear_penalty))) {
    restore();
    return 0;
  }
  // The last detection may have found points again, locked: they slide with their group too.
  if (const SlidingGroups g = sliding_groups(s, ctx.contacts, settled, held); g.resolved && g.any)
    slide_whole_faces(s, ctx.contacts, g, step);
  set_velocities(true);
  return pass;
}

}  // namespace ddafit
