// A scene's mirror image in the vertical axis (x -> -x), a check of how much a run's answer
// depends on the order in which the solvers meet its blocks and contacts. The physics of the
// mirror is the physics of the scene; what changes is that order: the broad phase sorts along
// x, each polygon's corners are numbered the other way round, and the narrow phase's
// tie-breaks, the Gauss-Seidel sweeps and the open-close iteration meet the blocks in the
// mirror's order. A difference between a run and its mirror is numerical, like the spread of
// an ensemble (forward/perturb.hpp; docs/speed-accuracy.md, "The mirror image").
#pragma once

#include <vector>

#include "forward/run_summary.hpp"
#include "forward/scene.hpp"

namespace ddafit {

// The scene reflected: every block's polygon (turned back counter-clockwise), velocity and
// spin, the measure points, gravity, a phreatic table (re-ordered by x) and an earthquake's
// horizontal acceleration. A scene cut from regions (io::read_scene cuts them) keeps its cut
// blocks and drops the regions: cutting the mirrored regions could give other blocks, and the
// mirror must be the same blocks. Mirroring twice gives the blocks, loads and points back.
Scene mirrored_scene(const Scene& scene);

// A mirrored run's history rows reflected back (positions, displacements, velocities), so
// that they read as the scene's own. The point summaries need nothing: they hold |u_x|, |u|,
// |v_x| and |v|.
void unmirror_history(std::vector<HistoryRow>& history);

}  // namespace ddafit
