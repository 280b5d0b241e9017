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
};

void assemble(const BlockSystem& system, const std::vector<Contact>& contacts,
              const StepParameters& step, BlockSparseMatrix& k, Eigen::VectorXd& f);

// Friction force magnitude of a sliding contact: N tan(phi) with phi degraded at the
// middle of the step's slip (seed Eq. 3 evaluated at d + |slip|/2, which keeps the
// lag of an explicit update out of the acceleration).
double sliding_friction_force(const BlockSystem& system, const Contact& contact);

}  // namespace ddafit
