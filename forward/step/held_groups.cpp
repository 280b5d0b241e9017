#include "forward/step/held_groups.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "forward/contact/contact_law.hpp"

namespace ddafit {

bool hold_stopped_groups(const BlockSystem& s, const SlidingGroups& g, const std::vector<Vec6>& velocities,
                         const Eigen::VectorXd& f, ContactSet& contacts, std::vector<char>& held) {
  const std::vector<double> along = net_force_along(s, g, f);
  std::vector<char> stopped(along.size(), 0);
  for (size_t k = 0; k < along.size(); ++k) stopped[k] = !g.tangent[k].isZero() && along[k] <= 0.0;
  // A group given a velocity is left as given (add_inertial_loads): friction slowing it is no hold.
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (g.group[b] >= 0 && velocities[b].head<3>().norm() != 0.0) stopped[g.group[b]] = 0;
  if (std::find(stopped.begin(), stopped.end(), 1) == stopped.end()) return false;
  for (ContactManifold& m : contacts.manifolds)
    for (const int b : {m.block_a, m.block_b}) {
      const int k = g.group[b];
      const int other = b == m.block_a ? m.block_b : m.block_a;
      if (k < 0 || !stopped[k] || g.group[other] == k || (g.group[other] < 0) != static_cast<bool>(g.on_ground[k]))
        continue;
      for (int q = 0; q < m.point_count; ++q)
        if (m.points[q].spring.state == ContactState::Sliding) m.points[q].spring.state = ContactState::Locked;
    }
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b)
    if (g.group[b] >= 0 && stopped[g.group[b]] && g.on_ground[g.group[b]]) held[b] = 1;
  return true;
}

bool holds_within_caps(const BlockSystem& s, const ContactSet& contacts, const std::vector<char>& settled,
                       const std::vector<char>& held, const Vec2& gravity, double shear_penalty) {
  const size_t n = s.blocks.size();
  std::vector<Vec2> shear(n, Vec2::Zero()), face(n, Vec2::Zero());
  std::vector<double> cohesion(n, 0.0), load(n, 0.0), mu(n, std::numeric_limits<double>::infinity());
  const auto member = [&](int b) { return s.blocks[b].unknown >= 0 && settled[b]; };
  for (const ContactManifold& m : contacts.manifolds)
    for (const int b : {m.block_a, m.block_b}) {
      const int other = b == m.block_a ? m.block_b : m.block_a;
      if (!held[b] || member(other)) continue;
      face[b] = side(m, b) * m.normal;  // from the ground towards b
      mu[b] = std::min(mu[b], m.friction);
      for (int q = 0; q < m.point_count; ++q) {
        const ContactPoint& p = m.points[q];
        if (p.spring.state == ContactState::Open) continue;
        shear[b] += side(m, b) * shear_penalty * p.spring.shear_offset * m.tangent;
        cohesion[b] += cohesive_strength(s.interfaces[m.interface], p);
      }
    }
  // What the free blocks resting on a held block press on it across its face.
  for (const ContactManifold& m : contacts.manifolds)
    for (const int b : {m.block_a, m.block_b}) {
      const int other = b == m.block_a ? m.block_b : m.block_a;
      if (!held[b] || !member(other) || face[b].isZero()) continue;
      for (int q = 0; q < m.point_count; ++q)
        if (m.points[q].spring.state != ContactState::Open)
          load[b] += m.points[q].spring.normal_force * std::max(0.0, -(side(m, b) * m.normal).dot(face[b]));
    }
  for (size_t b = 0; b < n; ++b) {
    if (!held[b] || face[b].isZero()) continue;
    const double normal = s.mass(static_cast<int>(b)) * std::max(0.0, -gravity.dot(face[b])) + load[b];
    if (shear[b].norm() > coulomb_cap(mu[b], normal, cohesion[b])) return false;
  }
  return true;
}

}  // namespace ddafit
