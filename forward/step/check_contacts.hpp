// Stage 4 of a step: re-classify every contact point from the solved displacements
// (Shi's open-close check): open / sliding / locked under the contact law
// (forward/contact/contact_law.hpp: Mohr-Coulomb with cohesion, tension cut-off, friction
// degraded by seed Eq. 2-3).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/step/assemble.hpp"

namespace ddafit {

// A contact that changed state this often within one step keeps its state for the
// rest of that step's open-close iteration.
constexpr int kFreezeAfterChanges = 2;

// A block that starts its step slower than this many times |g| dt, the speed gravity adds
// in one step, is starting to move (or at rest): its step's move is of the size of the slip
// a capped lock still holds back, so that slip is not left at the pass limit
// (open_close_iterate.cpp, kStartingExtraPasses).
constexpr double kStartingSpeedRatio = 1.0;

// A contact point: manifold and point index within it (for diagnoses).
struct PointRef {
  int manifold = -1;
  int point = -1;
};

struct ContactCheck {
  int frozen = 0;                 // points held in their state because they cycle
  int changed = 0;                // points whose state differs from the last iterate
  int capped = 0;                 // frozen locked points softened to their cap (check_contacts.cpp)
  int capped_starting = 0;        // of them, points between blocks starting to move (kStartingSpeedRatio)
  PointRef first_changed;         // one of them, for diagnoses
  double max_force_change = 0.0;  // largest change of a sliding point's N / largest N
  // Largest excess of a capped lock's shear force over its Coulomb cap in this iterate,
  // |k_s (d_s0 + d_s)| - (N tan(phi) + c l), over the largest N (judge_step.cpp).
  double cap_excess = 0.0;
};

// `shapes` and `slop` (the detection's) judge open vertex-vertex points whose corners pass
// each other over the step: they stay open whatever their gap along the corners' line
// (forward/contact/corner_paths.hpp).
ContactCheck check_contacts(const BlockSystem& system, const ContactShapes& shapes, double slop, ContactSet& contacts,
                            const Eigen::VectorXd& d, const StepParameters& step);

}  // namespace ddafit
