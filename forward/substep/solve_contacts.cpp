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

// Applies impulse P along (wa, wb): v_a -= P wa, v_b += P wb.
inline void apply(Vec6& va, Vec6& vb, const Vec6& wa, const Vec6& wb, double impulse) {
  va.noalias() -= impulse * wa;
  vb.noalias() += impulse * wb;
}

}  // namespace

ContactSoftness make_softness(double hertz, double zeta, double h) {
  if (hertz <= 0.0) return {0.0, 1.0, 0.0};
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * zeta + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

void warm_start(const std::vector<SubstepManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                BlockSystem& s) {
  for_each_coloured(colours, [&](int k) {
    const SubstepManifold& m = manifolds[k];
    Vec6& va = s.blocks[m.block_a].velocity;
    Vec6& vb = s.blocks[m.block_b].velocity;
    for (int q = 0; q < m.point_count; ++q) {
      const SubstepPoint& p = m.points[q];
      apply(va, vb, p.wa_n, p.wb_n, p.normal_impulse);
      apply(va, vb, p.wa_t, p.wb_t, p.tangent_impulse);
    }
  });
}

void solve_contacts(std::vector<SubstepManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                    const std::vector<Vec6>& step_moves, const SweepSettings& st, BlockSystem& s) {
  const double inv_h = 1.0 / st.h;
  for_each_coloured(colours, [&](int k) {
    SubstepManifold& m = manifolds[k];
    Vec6& va = s.blocks[m.block_a].velocity;
    Vec6& vb = s.blocks[m.block_b].velocity;
    const Vec6& da = step_moves[m.block_a];
    const Vec6& db = step_moves[m.block_b];
    for (int q = 0; q < m.point_count; ++q) {
      SubstepPoint& p = m.points[q];
      // Normal: the gap now, from the step's start and the blocks' moves since.
      const double gap = p.separation + p.jb_n.dot(db) - p.ja_n.dot(da);
      double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
      if (gap > 0.0) {
        bias = gap * inv_h;  // speculative: may close the gap within the substep, not more
      } else if (st.use_bias) {
        bias = std::max(st.softness.bias_rate * std::min(0.0, gap + st.linear_slop), -st.max_pushout_speed);
        mass_scale = st.softness.mass_scale;
        impulse_scale = st.softness.impulse_scale;
      }
      const double vn = p.jb_n.dot(vb) - p.ja_n.dot(va);
      const double change = -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
      // Contact law: compression only, unless a bond holds tension (forward/contact_law.hpp).
      const double total = std::max(p.normal_impulse + change, -p.tension_impulse);
      apply(va, vb, p.wa_n, p.wb_n, total - p.normal_impulse);
      p.normal_impulse = total;

      // Friction: Coulomb's cap mu N (seed Eq. 2-3 for mu) plus cohesion while bonded.
      const double cap = p.friction * std::max(p.normal_impulse, 0.0) + p.cohesion_impulse;
      const double vt = p.jb_t.dot(vb) - p.ja_t.dot(va);
      const double tangent = std::clamp(p.tangent_impulse - p.tangent_mass * vt, -cap, cap);
      apply(va, vb, p.wa_t, p.wb_t, tangent - p.tangent_impulse);
      p.tangent_impulse = tangent;
    }
  });
}

void advance_slip(const BlockSystem& s, const std::vector<Vec6>& moves, std::vector<SubstepManifold>& manifolds) {
  const long n = static_cast<long>(manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    SubstepManifold& m = manifolds[k];
    const Vec6& da = moves[m.block_a];
    const Vec6& db = moves[m.block_b];
    for (int q = 0; q < m.point_count; ++q) {
      SubstepPoint& p = m.points[q];
      p.step_normal_impulse += p.normal_impulse;
      p.step_tangent_impulse += p.tangent_impulse;
      if (p.normal_impulse <= 0.0) {
        p.last_slip = 0.0;
        if (p.normal_impulse < 0.0 || p.tension_impulse == 0.0) p.bonded = false;
        continue;
      }
      p.last_slip = std::abs(p.jb_t.dot(db) - p.ja_t.dot(da));
      const double cap = p.friction * p.normal_impulse + p.cohesion_impulse;
      const bool sliding = std::abs(p.tangent_impulse) >= 0.999 * cap;
      if (sliding && p.bonded) {
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
