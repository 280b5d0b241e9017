#include "forward/substep/solve_contacts.hpp"
#include "forward/substep/parallel.hpp"

#include <algorithm>
#include <cmath>

#include "forward/substep/prepare_contacts.hpp"

namespace ddafit {
namespace {

// Runs body(k) for every manifold, colour by colour. Within a colour no two manifolds
// share a moving block, so the order (and the thread count) does not change the numbers.
template <class Body>
void for_each_coloured(const std::vector<std::vector<int>>& colours, Body&& body) {
  for (int c = 0; c < static_cast<int>(colours.size()); ++c) {
    const std::vector<int>& members = colours[c];
    const long n = static_cast<long>(members.size());
    if (c == kSerialColour) {
      for (long k = 0; k < n; ++k) body(members[k]);
      continue;
    }
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
    for (long k = 0; k < n; ++k) body(members[k]);
  }
}

// Applies impulse P (a vector) at the point: -P on block a, +P on block b.
inline void apply(Vec3& va, Vec3& vb, const BlockMass& ma, const BlockMass& mb, const SubstepPoint& p,
                  const Vec2& impulse) {
  va[0] -= ma.inverse_mass * impulse.x();
  va[1] -= ma.inverse_mass * impulse.y();
  va[2] -= ma.inverse_inertia * cross2(p.ra, impulse);
  vb[0] += mb.inverse_mass * impulse.x();
  vb[1] += mb.inverse_mass * impulse.y();
  vb[2] += mb.inverse_inertia * cross2(p.rb, impulse);
}

}  // namespace

ContactSoftness make_softness(double hertz, double zeta, double h) {
  if (hertz <= 0.0) return {0.0, 1.0};
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * zeta + h * omega;
  const double a2 = h * omega * a1;
  return {omega / a1, a2 / (1.0 + a2)};
}

void warm_start(const std::vector<SubstepManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                SweepState& st) {
  for_each_coloured(colours, [&](int k) {
    const SubstepManifold& m = manifolds[k];
    Vec3& va = st.velocity[m.block_a];
    Vec3& vb = st.velocity[m.block_b];
    for (int q = 0; q < m.point_count; ++q) {
      const SubstepPoint& p = m.points[q];
      apply(va, vb, st.masses[m.block_a], st.masses[m.block_b], p,
            p.normal_impulse * m.normal + p.tangent_impulse * m.tangent);
    }
  });
}

void solve_contacts(std::vector<SubstepManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                    const SweepSettings& settings, SweepState& st) {
  const double inv_h = 1.0 / settings.h;
  for_each_coloured(colours, [&](int k) {
    SubstepManifold& m = manifolds[k];
    Vec3& va = st.velocity[m.block_a];
    Vec3& vb = st.velocity[m.block_b];
    const BlockMass& ma = st.masses[m.block_a];
    const BlockMass& mb = st.masses[m.block_b];
    for (int q = 0; q < m.point_count; ++q) {
      SubstepPoint& p = m.points[q];
      // Normal: the gap now, from the step's start and the blocks' moves since.
      const double gap = current_gap(m, p, st.step_moves);
      // The push-out of an overlap follows the soft spring (bias rate and mass scale), but
      // the impulse is not relaxed towards zero as Box2D's soft contact does: that leak
      // makes the overlap that holds a load F equal F / (m w^2), and with m the effective
      // mass of a small block under a 200 m thick mass it sank a 3 m triangle 0.9 m into
      // the bedrock (Vajont section VII stopped at 5.6-23 s; without it the run finishes).
      double bias = 0.0, mass_scale = 1.0;
      if (gap > 0.0) {
        bias = gap * inv_h;  // speculative: may close the gap within the substep, not more
      } else if (settings.use_bias) {
        bias = std::max(settings.softness.bias_rate * std::min(0.0, gap + settings.linear_slop),
                        -settings.max_pushout_speed);
        mass_scale = settings.softness.mass_scale;
      }
      const double vn = m.normal.dot(velocity_at(vb, p.rb) - velocity_at(va, p.ra));
      const double change = -p.normal_mass * mass_scale * (vn + bias);
      // Contact law: compression only, unless a bond holds tension (forward/contact_law.hpp).
      const double total = std::max(p.normal_impulse + change, -p.tension_impulse);
      apply(va, vb, ma, mb, p, (total - p.normal_impulse) * m.normal);
      p.normal_impulse = total;

      // Friction: Coulomb's cap mu N (seed Eq. 2-3 for mu) plus cohesion while bonded.
      const double cap = p.friction * std::max(p.normal_impulse, 0.0) + p.cohesion_impulse;
      const double vt = m.tangent.dot(velocity_at(vb, p.rb) - velocity_at(va, p.ra));
      const double tangent = std::clamp(p.tangent_impulse - p.tangent_mass * vt, -cap, cap);
      apply(va, vb, ma, mb, p, (tangent - p.tangent_impulse) * m.tangent);
      p.tangent_impulse = tangent;
    }
  });
}

void advance_slip(const BlockSystem& s, const std::vector<Vec3>& moves, std::vector<SubstepManifold>& manifolds) {
  const long n = static_cast<long>(manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    SubstepManifold& m = manifolds[k];
    for (int q = 0; q < m.point_count; ++q) {
      SubstepPoint& p = m.points[q];
      p.step_normal_impulse += p.normal_impulse;
      p.step_tangent_impulse += p.tangent_impulse;
      if (p.normal_impulse <= -0.999 * p.tension_impulse) {
        // Open (or torn at its tensile strength): no slip, and the bond is gone.
        p.last_slip = 0.0;
        p.bonded = false;
        p.cohesion_impulse = p.tension_impulse = 0.0;
        continue;
      }
      p.last_slip = std::abs(m.tangent.dot(velocity_at(moves[m.block_b], p.rb) - velocity_at(moves[m.block_a], p.ra)));
      const double cap = p.friction * std::max(p.normal_impulse, 0.0) + p.cohesion_impulse;
      if (p.bonded && std::abs(p.tangent_impulse) >= 0.999 * cap) {
        p.bonded = false;  // cohesion and tension are lost once the contact slides
        p.cohesion_impulse = p.tension_impulse = 0.0;
      }
      if (p.slip >= p.critical_distance && p.last_slip == 0.0) continue;
      p.slip += p.last_slip;  // seed Eq. 2: d accumulates while the point touches
      if (p.slip < p.critical_distance + p.last_slip) update_friction(s, m, p);
    }
  }
}

}  // namespace ddafit
