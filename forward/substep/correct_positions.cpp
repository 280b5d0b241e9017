// Stage 6 of a substep-solver step, once after its substeps: the position correction of deep
// overlaps (solve_contacts.hpp, PositionCorrection, says what and why).
#include <algorithm>

#include "forward/substep/solve_contacts.hpp"

namespace ddafit {
namespace {

// Position correction: the largest ratio of two free blocks' inverse masses it uses.
constexpr double kCorrectionMassRatio = 1.0;

}  // namespace

void correct_positions(const std::vector<ContactManifold>& manifolds, const PositionCorrection& settings,
                       SweepState& st) {
  // The deep manifolds and every other manifold of their blocks: a correction that moves a
  // block may push it into another neighbour, and that overlap is corrected in the same pass.
  std::vector<char> involved;
  std::vector<int> list = deep_neighbourhood(manifolds, st, involved);
  if (list.empty()) return;
  // A correction also moves the block on the far side of a listed manifold, and may push it
  // into a neighbour of its own: that block's manifolds join the list as it moves. Without
  // this, on Vajont section III degraded a correction of slide_00446 against one heavy block
  // pressed it 5 cm (0.9 % of its size) into another that the list did not hold.
  // The block-to-manifold index (kept for the step) is looked up only when a block outside
  // the list first moves.
  const BlockManifolds* of_block = nullptr;
  std::vector<char> listed;
  const auto bring_in = [&](int b) {
    if (involved[b] || !st.masses[b].moves) return;
    if (!of_block) {
      of_block = &block_manifolds(manifolds, st);
      listed.assign(manifolds.size(), 0);
      for (const int k : list) listed[k] = 1;
    }
    involved[b] = 1;
    for (int i = of_block->first[b]; i < of_block->first[b + 1]; ++i)
      if (!listed[of_block->ids[i]]) listed[of_block->ids[i]] = 1, list.push_back(of_block->ids[i]);
  };
  // `passes` passes, then up to `extra_passes` more while the last one still corrected.
  const int most = settings.passes + settings.extra_passes;
  bool corrected = true;
  for (int pass = 0; pass < settings.passes || (corrected && pass < most); ++pass) {
    corrected = false;
    for (size_t i = 0; i < list.size(); ++i) {
      const ContactManifold& m = manifolds[list[i]];
      BlockMass ma = st.masses[m.block_a], mb = st.masses[m.block_b];
      // Shared between the blocks as an impulse would be, but with the lighter block's
      // inverse mass and inertia capped at kCorrectionMassRatio times the heavier one's: a
      // small block wedged between two large ones is otherwise moved from one overlap into
      // the other while the large ones hardly part.
      if (ma.moves && mb.moves) {
        const double cap = kCorrectionMassRatio * std::min(ma.inverse_mass, mb.inverse_mass);
        BlockMass& light = ma.inverse_mass > mb.inverse_mass ? ma : mb;
        if (light.inverse_mass > cap) {
          const double scale = cap / light.inverse_mass;
          light.inverse_mass *= scale;
          light.inverse_inertia *= scale;
        }
      }
      Vec3& da = st.step_moves[m.block_a];
      Vec3& db = st.step_moves[m.block_b];
      bool moved = false;
      for (int q = 0; q < m.point_count; ++q) {
        const ContactPoint& p = m.points[q];
        const double excess = -current_gap(m, p, st.step_moves) - m.deep_overlap;
        if (excess <= 0.0) continue;
        const double correction = std::min(settings.fraction * excess, settings.max_correction);
        const double ca = cross2(p.ra, m.normal), cb = cross2(p.rb, m.normal);
        const double k_n =
            ma.inverse_mass + mb.inverse_mass + ma.inverse_inertia * ca * ca + mb.inverse_inertia * cb * cb;
        if (k_n > 0.0) apply_impulse(da, db, ma, mb, p, (correction / k_n) * m.normal), moved = true;
      }
      if (moved) corrected = true, bring_in(m.block_a), bring_in(m.block_b);
    }
  }
}

}  // namespace ddafit
