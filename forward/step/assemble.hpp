// Stage 2 of a step: the global system K D = F from the blocks (inertia, elasticity,
// carried stress, gravity) and from the contacts in their current open-close state.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact.hpp"
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
};

void assemble(const BlockSystem& system, const std::vector<Contact>& contacts,
              const StepParameters& step, BlockSparseMatrix& k, Eigen::VectorXd& f);

// Friction force magnitude of a sliding contact: N tan(phi) with phi degraded at the
// middle of the step's slip (seed Eq. 3 at d + |slip|/2, the slip predicted by the last
// accepted step's), which keeps the lag of an explicit update out of the acceleration.
double sliding_friction_force(const BlockSystem& system, const Contact& contact);

}  // namespace ddafit
