// Stage 4 of a step: re-classify every contact from the solved displacements
// (Shi's open-close check): open / sliding / locked under Mohr-Coulomb with cohesion
// and tensile strength, friction degraded by seed Eq. 3.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact.hpp"
#include "forward/step/assemble.hpp"

namespace ddafit {

// A contact that changed state this often within one step keeps its state for the
// rest of that step's open-close iteration.
constexpr int kFreezeAfterChanges = 2;

struct ContactCheck {
  int frozen = 0;                 // contacts held in their state because they cycle
  int changed = 0;                // contacts whose state differs from the last iterate
  int first_changed = -1;         // index of one of them, for diagnoses
  double max_force_change = 0.0;  // largest change of a sliding contact's N / largest N
};

ContactCheck check_contacts(const BlockSystem& system, std::vector<Contact>& contacts,
                            const Eigen::VectorXd& d, const StepParameters& step);

}  // namespace ddafit
