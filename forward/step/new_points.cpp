#include "forward/step/new_points.hpp"

#include <cmath>

#include "forward/step/assemble.hpp"

namespace ddafit {

double relative_slide(const BlockSystem& s, const ContactManifold& m, const ContactPoint& p) {
  const Block& a = s.blocks[m.block_a];
  const Block& b = s.blocks[m.block_b];
  const Vec2 vb = b.unknown >= 0 ? Vec2(displacement_matrix(p.anchor, b.centroid) * b.velocity) : Vec2::Zero();
  const Vec2 va = a.unknown >= 0 ? Vec2(displacement_matrix(p.anchor, a.centroid) * a.velocity) : Vec2::Zero();
  return m.tangent.dot(vb - va);
}

void start_new_points(const BlockSystem& s, ContactSet& contacts, double dt, double slip_tolerance) {
  for (ContactManifold& m : contacts.manifolds) {
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      if (!p.fresh || p.spring.state == ContactState::Open) continue;
      const double slide = relative_slide(s, m, p) * dt;
      if (std::abs(slide) <= slip_tolerance) continue;
      p.spring.state = p.spring.step_state = ContactState::Sliding;
      p.spring.slip_direction = slide > 0.0 ? 1.0 : -1.0;
      p.spring.normal_force = 0.0;
      p.spring.shear_offset = 0.0;
    }
  }
}

void start_impact_slides(const BlockSystem& s, ContactSet& contacts, const std::vector<char>& struck, double dt,
                         double slip_tolerance, double shear_penalty) {
  for (ContactManifold& m : contacts.manifolds) {
    if (!struck[m.block_a] && !struck[m.block_b]) continue;
    for (int q = 0; q < m.point_count; ++q) {
      ContactPoint& p = m.points[q];
      SpringState& c = p.spring;
      if (c.state != ContactState::Locked || p.bonded) continue;
      const double slide = relative_slide(s, m, p) * dt;
      if (std::abs(slide) <= slip_tolerance) continue;
      c.state = c.step_state = ContactState::Sliding;
      c.slip_direction = slide > 0.0 ? 1.0 : -1.0;
      c.shear_offset = sliding_shear_offset(s.interfaces[m.interface], m, p, shear_penalty);
    }
  }
}

}  // namespace ddafit
