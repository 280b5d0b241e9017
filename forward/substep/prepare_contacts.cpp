#include "forward/substep/prepare_contacts.hpp"
#include "forward/substep/parallel.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <bit>
#include <cstdint>

#include "forward/contact_law.hpp"
#include "forward/mass_matrix.hpp"

namespace ddafit {
void compute_block_masses(const BlockSystem& s, std::vector<BlockMass>& masses) {
  masses.resize(s.blocks.size());
  const long n = static_cast<long>(s.blocks.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    const Block& block = s.blocks[b];
    BlockMass& out = masses[b];
    out = BlockMass{};
    if (block.fixed) continue;
    out.moves = true;
    // The rigid-body rows of the DDA mass matrix: translation and rotation about the
    // centroid (forward/mass_matrix.hpp); the strain unknowns carry no inertia here.
    const Mat3 m = s.density[block.material] * unit_mass_matrix(block).topLeftCorner<3, 3>();
    out.inverse.topLeftCorner<3, 3>() = m.inverse();
  }
}

void update_friction(const BlockSystem& s, const SubstepManifold& m, SubstepPoint& p) {
  const Interface& face = s.interfaces[m.interface];
  p.friction = friction_coefficient(face, p.slip + 0.5 * p.last_slip, p.critical_distance);
}

void prepare_contacts(const BlockSystem& s, const std::vector<BlockMass>& masses, double h,
                      std::vector<SubstepManifold>& manifolds) {
  const long n = static_cast<long>(manifolds.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long k = 0; k < n; ++k) {
    SubstepManifold& m = manifolds[k];
    const Block& a = s.blocks[m.block_a];
    const Block& b = s.blocks[m.block_b];
    const BlockMass& ma = masses[m.block_a];
    const BlockMass& mb = masses[m.block_b];
    const Interface& face = s.interfaces[m.interface];
    for (int q = 0; q < m.point_count; ++q) {
      SubstepPoint& p = m.points[q];
      // v_rel = T_b(p) v_b - T_a(p) v_a (Shi 1993 eq. 2.2), projected on n and t.
      p.ja_n = displacement_matrix_transpose_times(p.anchor, a.centroid, m.normal);
      p.jb_n = displacement_matrix_transpose_times(p.anchor, b.centroid, m.normal);
      p.ja_t = displacement_matrix_transpose_times(p.anchor, a.centroid, m.tangent);
      p.jb_t = displacement_matrix_transpose_times(p.anchor, b.centroid, m.tangent);
      p.wa_n = ma.inverse * p.ja_n;
      p.wb_n = mb.inverse * p.jb_n;
      p.wa_t = ma.inverse * p.ja_t;
      p.wb_t = mb.inverse * p.jb_t;
      const double kn = p.ja_n.dot(p.wa_n) + p.jb_n.dot(p.wb_n);
      const double kt = p.ja_t.dot(p.wa_t) + p.jb_t.dot(p.wb_t);
      p.normal_mass = kn > 0.0 ? 1.0 / kn : 0.0;
      p.tangent_mass = kt > 0.0 ? 1.0 / kt : 0.0;
      update_friction(s, m, p);
      p.step_normal_impulse = p.step_tangent_impulse = 0.0;
      p.tension_impulse = h * tensile_capacity(face, p.bonded, p.bond_length);
      p.cohesion_impulse = p.bonded ? h * face.cohesion * p.bond_length : 0.0;
    }
  }
}

std::vector<std::vector<int>> colour_manifolds(const BlockSystem& s, const std::vector<SubstepManifold>& manifolds) {
  std::vector<std::vector<int>> colours(kSerialColour + 1);
  std::vector<std::uint64_t> used(s.blocks.size(), 0);
  for (int k = 0; k < static_cast<int>(manifolds.size()); ++k) {
    const SubstepManifold& m = manifolds[k];
    const bool fa = s.blocks[m.block_a].fixed, fb = s.blocks[m.block_b].fixed;
    // A fixed block never changes velocity, so it does not constrain the colouring.
    const std::uint64_t taken = (fa ? 0 : used[m.block_a]) | (fb ? 0 : used[m.block_b]);
    const int colour = taken == ~std::uint64_t{0} ? kSerialColour : std::countr_one(taken);
    if (colour < kSerialColour) {
      if (!fa) used[m.block_a] |= std::uint64_t{1} << colour;
      if (!fb) used[m.block_b] |= std::uint64_t{1} << colour;
    }
    colours[std::min(colour, kSerialColour)].push_back(k);
  }
  while (!colours.empty() && colours.back().empty()) colours.pop_back();
  return colours;
}

}  // namespace ddafit
