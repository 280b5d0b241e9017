#include "forward/substep/block_stress.hpp"
#include "forward/substep/parallel.hpp"

#include <Eigen/LU>

#include "forward/step/update_blocks.hpp"

namespace ddafit {

void update_block_stress(BlockSystem& s, const std::vector<SubstepManifold>& manifolds,
                         const std::vector<char>& deformable, double duration, bool last_substep,
                         double relaxation) {
  // Sum of the contact forces' first moments per block; the strain rows of the point's
  // Jacobians are exactly T_s(p)^T n and T_s(p)^T t at the start of the step.
  std::vector<Vec3> moment(s.blocks.size(), Vec3::Zero());
  for (const SubstepManifold& m : manifolds) {
    for (int q = 0; q < m.point_count; ++q) {
      const SubstepPoint& p = m.points[q];
      const double pn = last_substep ? p.normal_impulse : p.step_normal_impulse;
      const double pt = last_substep ? p.tangent_impulse : p.step_tangent_impulse;
      moment[m.block_b] += pn * p.jb_n.segment<3>(3) + pt * p.jb_t.segment<3>(3);
      moment[m.block_a] -= pn * p.ja_n.segment<3>(3) + pt * p.ja_t.segment<3>(3);
    }
  }
  const long n = static_cast<long>(s.blocks.size());
#pragma omp parallel for schedule(static) if (n >= kParallelMinimum)
  for (long b = 0; b < n; ++b) {
    Block& block = s.blocks[b];
    if (block.fixed || !deformable[block.material]) continue;
    // Relaxed towards the contacts' mean stress rather than set to it: the step's
    // impulses are noisy, and a strain that follows them at once overlapped neighbours,
    // whose push-out raised the impulses again (Vajont section I gained energy in 0.05 s).
    const Vec3 target = moment[b] / (duration * block.area);
    const Vec3 stress = block.stress + relaxation * (target - block.stress);
    const Mat3& c = s.elastic[block.material];
    Vec6 d = Vec6::Zero();
    d.segment<3>(3) = c.partialPivLu().solve(stress - block.stress);
    displace_block(s, static_cast<int>(b), d, true);
  }
}

}  // namespace ddafit
