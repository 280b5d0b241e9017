// Stage 4 of a substep-solver step, run in every substep: the contact impulses. The
// sweeps follow Box2D v3's soft step (Catto, "Solver2D"): warm start with the impulses of
// the last substep, one sweep with a soft push-out of overlaps, and, after the blocks
// have moved, one relax sweep without it so that no push-out velocity is kept.
#pragma once

#include <vector>

#include "forward/block_system.hpp"
#include "forward/substep/substep_types.hpp"

namespace ddafit {

// A soft constraint as a spring of `hertz` and damping ratio `zeta` resolved over a
// substep h (Box2D's b2Softness): with w = 2 pi hertz, a1 = 2 zeta + h w, a2 = h w a1,
// the push-out velocity is bias_rate x overlap, and the impulse is scaled by mass_scale
// and relaxed towards zero by impulse_scale.
struct ContactSoftness {
  double bias_rate = 0.0;      // 1/s: w / a1
  double mass_scale = 1.0;     // a2 / (1 + a2)
  double impulse_scale = 0.0;  // 1 / (1 + a2)
};
ContactSoftness make_softness(double hertz, double zeta, double h);

struct SweepSettings {
  double h = 0.0;                 // substep, s
  ContactSoftness softness;
  double max_pushout_speed = 0.0;  // m/s: an overlap is pushed out no faster than this
  double linear_slop = 0.0;        // m: overlap tolerated without push-out (stops jitter)
  bool use_bias = true;            // false in the relax sweep
};

// The velocities of every block change by W J^T P for each point's impulse P. `step_moves`
// holds each block's displacement so far in the step (first order, as T), from which the
// current gap of each point follows without new geometry.
void warm_start(const std::vector<SubstepManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                BlockSystem& system);
void solve_contacts(std::vector<SubstepManifold>& manifolds, const std::vector<std::vector<int>>& colours,
                    const std::vector<Vec6>& step_moves, const SweepSettings& settings, BlockSystem& system);

// After a substep moved the blocks by `moves`: the slip of each touching point (seed Eq. 2)
// and, where it changed, its friction coefficient; a bond is lost once its point slides or opens.
void advance_slip(const BlockSystem& system, const std::vector<Vec6>& moves, std::vector<SubstepManifold>& manifolds);

}  // namespace ddafit
