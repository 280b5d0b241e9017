// Stage 0b, straight after the settling of settle_contacts.hpp: blocks that start the run
// sliding are settled again as they will move.
//
// Settling holds every point locked, so a block on a face steeper than its friction is held by
// shear springs carrying its whole weight along the face, m g sin(alpha). At t = 0 those points
// start sliding at their cap, tan(phi) N (load_springs), but the block keeps what the locked
// settling gave it: normal forces shared between its corners so as to balance the moment of the
// locked shear, and the strain that shear put into it. Released together, the difference sets
// the block rocking and shearing on its penalty springs, undamped by the time scheme once the
// step resolves them (docs/theory.md, Known limits (a)). It grows with the block: a 200 x 50 m
// block on a 35 deg face (even without friction) stopped at its 9th step on "contacts are
// creating energy"; 90 x 24 m blocks ran 5-100 % off seed Eq. 4; a 10 m block 12 %.
//
// Here the settling is done again with the sliding points at their cap (and the points of a group
// whose weight along its one face exceeds that face's caps, set sliding), in the frame of each
// sliding group (the settled free blocks joined by their loaded points that do not slide): each
// block carries d'Alembert's load -m_i a, a the group's acceleration along the face it slides on,
// the net force along that face over the group's mass (seed Eq. 4 for one block). Groups joined
// by a sliding point (a block on a weaker joint of the block beneath it) take their own
// accelerations; a group whose net force points against its slip is held, its sliding points
// locked (model revision 2026-12-06.9), and settled with them so (.06.11: a block held on a
// slope whose rear corner passed its cap in the first settling). Each group is then in
// equilibrium, and the settling finds the normal forces, rotations and strains it slides (or
// rests) with. The stage leaves the settled state as it was when any group slides on faces that
// are not parallel (no one acceleration along them: the Vajont sections' masses), when no group
// slides or is held, or one is given a velocity, or when a pass fails or would move a block too
// far. docs/theory.md §6, "Blocks that start sliding".
#pragma once

#include <vector>

#include "forward/step/assemble.hpp"
#include "forward/step/implicit_context.hpp"

namespace ddafit {

// `settled`: per block, whether settle_contacts moved it (resting on the ground, not falling).
// Returns the passes run (0 when no group slides or one slides on two faces). The state is left
// as it was if a pass would move a block by more than `max_shift` or the solver fails.
int settle_sliding_groups(ImplicitStepContext& ctx, const StepParameters& relaxed, const StepParameters& step,
                          const std::vector<char>& settled, double max_shift);

}  // namespace ddafit
