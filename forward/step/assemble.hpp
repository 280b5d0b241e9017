// Stage 2 of a step: the global system K D = F from the blocks (inertia, elasticity,
// carried stress, gravity) and from the contacts in their current open-close state.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_law.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/sparse_system.hpp"

namespace ddafit {

struct StepParameters {
  double time_step = 0.0;      // s
  double penalty = 0.0;        // normal contact spring, N/m
  double shear_penalty = 0.0;  // shear spring of locked contacts, N/m
  Vec2 gravity = Vec2::Zero();
  // Contact tolerance, m: an open contact closes only when it penetrates deeper, and a
  // sliding contact locks only when it slips back further. Contacts that carry almost
  // no load otherwise flip state on gaps and slips of 1e-9 m set by the rest of the
  // system, and the open-close iteration never settles (a standing brick wall needed
  // 70 step cuts in 0.05 s without it).
  double contact_tolerance = 0.0;
  // Largest part of a contact's penetration at the start of the step that its spring
  // may push out within the step, m (SimulationOptions::max_pushout_speed x dt).
  double pushout = 1e300;
  // The ground's mean acceleration over the step (forward/earthquake/ground_motion.hpp): in
  // the ground's frame every free block carries -m a_g at its centroid.
  Vec2 ground_acceleration = Vec2::Zero();
};

// The gap at which a contact's normal spring is unloaded during this step: 0, except for
// a contact that starts the step deeper than it can be pushed out within the step (a corner
// that came round a corner, found already inside). Pushing all of that out in one step would
// release the spring's energy as a kick (0.4 m at the Vajont penalty threw blocks at 1000 m/s);
// shifting the spring's zero pushes the overlap out at a bounded speed instead, as game
// engines cap their push-out velocity. What may be pushed out is step.pushout beyond the
// overlap the point's load held at the start of the step (start_force / penalty): that overlap
// is the spring at rest under its load, not an overlap to push out. Capped with the rest, a
// resting point could hold no more than penalty x pushout, which falls with the step: a
// 200 x 50 m block on a 35 deg face (resting overlap 0.5 mm) sank and rocked at 0.37 ms steps
// (pushout 0.37 mm) and ran 78 % off seed Eq. 4 (model revision 2026-12-06.6).
inline double spring_reference(const ContactPoint& p, const StepParameters& step) {
  return std::min(0.0, p.separation + step.pushout + p.spring.start_force / step.penalty);
}

// K D = F of one attempt: K and F from assemble(), D from the solve.
struct GlobalSystem {
  BlockSparseMatrix k;
  Eigen::VectorXd f;
  Eigen::VectorXd d;
};

// K and F of `equations` for the contacts' current states (D is left alone).
void assemble(const BlockSystem& system, const ContactSet& contacts, const StepParameters& step,
              GlobalSystem& equations);

// The shear stiffness of a locked point: k_s, or the share of it a capped lock keeps
// (check_contacts.cpp, "Capped locks").
inline double locked_shear_stiffness(const SpringState& c, const StepParameters& step) {
  return c.shear_scale * step.shear_penalty;
}

// Friction force magnitude of a sliding point: the Mohr-Coulomb cap N tan(phi) + c l_c, phi
// from its face's slip history predicted to the middle of the step (seed Eq. 2-3), the
// cohesion while the point is still bonded: a bond lasts until the point has slid by more
// than the slop (forward/contact/contact_law.hpp, wear_bond).
inline double sliding_friction_force(const Interface& face, const ContactManifold& m, const ContactPoint& p) {
  return coulomb_cap(m.friction, p.spring.normal_force, cohesive_strength(face, p));
}

// d_s0 of a point that starts (or goes on) sliding: its shear spring trails the slip by the
// friction force over its stiffness, s N tan(phi) / k_s, so that should the point lock, the
// spring takes over at the friction force instead of at zero (a sudden loss of resistance at
// every stick feeds stick-slip vibration at short steps). One formula for the three places a
// point slides: settling (settle_contacts.cpp), an impact (new_points.cpp), a step's end
// (update_blocks.cpp).
inline double sliding_shear_offset(const Interface& face, const ContactManifold& m, const ContactPoint& p,
                                   double shear_penalty) {
  return p.spring.slip_direction * sliding_friction_force(face, m, p) / shear_penalty;
}

}  // namespace ddafit
