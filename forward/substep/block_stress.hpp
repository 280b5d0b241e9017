// Stage 5 of a substep-solver step: each deformable block's stress and strain.
//
// The strain unknowns carry no inertia in the substep solver (their elastic periods,
// milliseconds for metre-size blocks, are far below the time scales of a slide). A
// block's strain is then in equilibrium with its contacts: the DDA equations of the
// three strain unknowns, -S sigma + sum of T_s(p)^T f_p = 0 (Shi 1993 ch. 2), say that
// the block's stress is the mean stress of its contact forces,
//   sigma = (1 / S) sum_p (X f_x, Y f_y, (Y f_x + X f_y) / 2),
// with (X, Y) the contact point about the centroid (Cauchy's mean-stress theorem; a
// uniform body force has no first moment about the centroid). The block then takes the
// strain C^-1 sigma: its vertices move by the change of strain, first order as in T.
// The forces are the contact impulses of the step divided by its length. Resolved
// instead, the elastic vibration fed friction a spurious oscillation that lowered the
// mean friction (the seed's incline slid 1.5 mm/s fast with 4 substeps, 9 with 16).
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/substep/substep_context.hpp"
#include "forward/substep/substep_types.hpp"

namespace ddafit {

// `deformable[m]`: material m keeps its strain unknowns (not rigid); with none (the
// default, control.rigid_blocks) nothing is done. The contact forces are the step's
// impulses over `duration`.
// `relaxation` in (0, 1]: the share of the way to the contacts' mean stress taken now.
// `measured` false (the quiet start): the measurement points' origins move with the strain.
// On ctx.system, from ctx.contacts, for the materials ctx.deformable marks.
void update_block_stress(SubstepContext& ctx, double duration, double relaxation, bool measured);

}  // namespace ddafit
