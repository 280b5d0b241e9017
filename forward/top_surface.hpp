// The ground surface a run leaves: the top of the blocks (fixed and free) along x, as a
// deposit is compared with a surveyed surface after a slide (docs/vajont.md, "The final
// configuration"). Sampled in kSurfaceColumns equal columns over the blocks' x extent.
#pragma once

#include <vector>

#include "forward/block_system.hpp"

namespace ddafit {

inline constexpr int kSurfaceColumns = 400;

// (x, z) at the middle of each column: the highest point of any block edge crossing that x
// (a column no block reaches is left out).
std::vector<Vec2> top_surface(const BlockSystem& system, int columns = kSurfaceColumns);

// Root mean square of (surface - reference) over the surface's columns with x in [from, to];
// NaN when no column lies there.
double surface_misfit_rms(const std::vector<Vec2>& surface, const std::vector<Vec2>& reference, double from, double to);

}  // namespace ddafit
