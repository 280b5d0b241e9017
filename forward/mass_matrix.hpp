// The mass matrix of a DDA block, shared by both solvers.
#pragma once

#include "forward/block_system.hpp"

namespace ddafit {

// Mass matrix of one block divided by density: the integral of T^T T over the block
// (formulation digest, "Inertia"), from the area and second moments about the centroid.
inline Mat6 unit_mass_matrix(const Block& b) {
  const double sxx = b.s_xx, syy = b.s_yy, sxy = b.s_xy;
  Mat6 m = Mat6::Zero();
  m(0, 0) = m(1, 1) = b.area;
  m(2, 2) = sxx + syy;
  m(2, 3) = m(3, 2) = -sxy;
  m(2, 4) = m(4, 2) = sxy;
  m(2, 5) = m(5, 2) = 0.5 * (sxx - syy);
  m(3, 3) = sxx;
  m(3, 5) = m(5, 3) = 0.5 * sxy;
  m(4, 4) = syy;
  m(4, 5) = m(5, 4) = 0.5 * sxy;
  m(5, 5) = 0.25 * (sxx + syy);
  return m;
}

}  // namespace ddafit
