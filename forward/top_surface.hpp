// The ground surface a run leaves: the top of the blocks (fixed and free) along x, as a
// deposit is compared with a surveyed surface after a slide (docs/vajont.md, "The final
// configuration"). Sampled in kSurfaceColumns equal columns over the blocks' x extent.
#pragma once

#include <vector>

#include "forward/block_system.hpp"

namespace ddafit {

inline constexpr int kSurfaceColumns = 400;

// Which blocks a surface is the top of: all (the ground a run leaves) or the fixed ones (the
// path the sled follows, forward/sled/sled.hpp).
enum class SurfaceOf { AllBlocks, FixedBlocks };

// (x, z) at the middle of each column over those blocks' x extent: the highest point of any of
// their edges crossing that x (a column none reaches is left out).
std::vector<Vec2> top_surface(const BlockSystem& system, int columns = kSurfaceColumns,
                              SurfaceOf of = SurfaceOf::AllBlocks);

// Root mean square of (surface - reference) over the surface's columns with x in [from, to];
// NaN when no column lies there.
double surface_misfit_rms(const std::vector<Vec2>& surface, const std::vector<Vec2>& reference, double from, double to);

}  // namespace ddafit
