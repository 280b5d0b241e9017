#include "forward/step/resolve_impacts.hpp"

#include <algorithm>
#include <vector>

#include "forward/contact/contact_law.hpp"

namespace ddafit {
namespace {

// Gauss-Seidel sweeps over the impact points: a block landing on two points, or a pair
// that lands on each other and on a third block, couples them.
constexpr int kSweeps = 8;

struct Impact {
  int manifold = -1, point = -1;
  double target = 0.0;         // normal speed that closes the gap at the end of the step, m/s
  double normal_mass = 0.0;    // 1 / (n W n), kg/m
  double tangent_mass = 0.0;   // 1 / (t W t)
  double normal = 0.0;         // accumulated impulses, N s/m
  double tangent = 0.0;
};

}  // namespace

int resolve_impacts(ImplicitStepContext& ctx, double dt) {
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
  // Velocity of block b's material point at r from its centroid (rigid part of T V).
  const auto velocity = [&](int b, const Vec2& r) -> Vec2 {
    return velocity_at(s.blocks[b].velocity.head<3>(), r);
  };
  const auto relative = [&](const ContactManifold& m, const ContactPoint& p) -> Vec2 {
    return velocity(m.block_b, p.rb) - velocity(m.block_a, p.ra);
  };
  const auto effective_mass = [&](const ContactManifold& m, const ContactPoint& p, const Vec2& axis) {
    return rigid_effective_mass(inverse_mass(m.block_a), inverse_inertia(m.block_a), inverse_mass(m.block_b),
                                inverse_inertia(m.block_b), p.ra, p.rb, axis);
  };
  std::vector<Impact> impacts;
  for (int k = 0; k < static_cast<int>(manifolds.size()); ++k) {
    const ContactManifold& m = manifolds[k];
    for (int q = 0; q < m.point_count; ++q) {
      const ContactPoint& p = m.points[q];
      const double target = -std::max(p.separation, 0.0) / dt;
      if (m.normal.dot(relative(m, p)) >= target) continue;
      const double normal_mass = effective_mass(m, p, m.normal);
      if (normal_mass > 0.0) impacts.push_back({k, q, target, normal_mass, effective_mass(m, p, m.tangent)});
    }
  }
  // P on block b at the point, -P on block a.
  const auto apply = [&](const ContactManifold& m, const ContactPoint& p, const Vec2& impulse) {
    Vec6& va = s.blocks[m.block_a].velocity;
    Vec6& vb = s.blocks[m.block_b].velocity;
    const double wa = inverse_mass(m.block_a), wb = inverse_mass(m.block_b);
    va[0] -= wa * impulse.x(), va[1] -= wa * impulse.y(), va[2] -= inverse_inertia(m.block_a) * cross2(p.ra, impulse);
    vb[0] += wb * impulse.x(), vb[1] += wb * impulse.y(), vb[2] += inverse_inertia(m.block_b) * cross2(p.rb, impulse);
  };
  for (int sweep = 0; sweep < kSweeps && !impacts.empty(); ++sweep) {
    for (Impact& i : impacts) {
      const ContactManifold& m = manifolds[i.manifold];
      const ContactPoint& p = m.points[i.point];
      const double vn = m.normal.dot(relative(m, p));
      const double normal = std::max(i.normal + i.normal_mass * (i.target - vn), 0.0);
      apply(m, p, (normal - i.normal) * m.normal);
      i.normal = normal;
      // Mohr-Coulomb (contact_law.hpp), no cohesion in an impact: |friction| <= tan(phi) x normal.
      const double cap = coulomb_cap(m.friction, i.normal, 0.0);
      const double vt = m.tangent.dot(relative(m, p));
      const double tangent = std::clamp(i.tangent - i.tangent_mass * vt, -cap, cap);
      apply(m, p, (tangent - i.tangent) * m.tangent);
      i.tangent = tangent;
    }
  }
  return static_cast<int>(impacts.size());
}

}  // namespace ddafit
