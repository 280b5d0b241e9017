// Corner-to-corner points read again before each substep (model revision 2026-12-06.19).
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/contact/contact_types.hpp"
#include "forward/substep/solve_contacts.hpp"

namespace ddafit {

// The substep solver's side of forward/contact/corner_paths.hpp. remember_corner_points lists
// the step's vertex-vertex points apart at detection with their gaps then (into
// `state.corner_points`). Before each substep, refresh_corner_gaps gives each listed point its
// gap from detection again and, where its corners pass each other within the substep at the
// blocks' velocities (corners_pass, grown by `slop`), raises it to what the pair can close in
// the substep, |relative velocity| h + slop, so that the point pushes nothing; the next
// step's detection reads the pair afresh.
void remember_corner_points(const std::vector<ContactManifold>& manifolds, SweepState& state);
void refresh_corner_gaps(const BlockSystem& s, const ContactShapes& shapes, double h, double slop,
                         std::vector<ContactManifold>& manifolds, SweepState& state);

}  // namespace ddafit
