#include "forward/substep/block_stress.hpp"
#include "forward/parallel.hpp"

#include <Eigen/LU>
#include <algorithm>

#include "forward/common/displace_block.hpp"

namespace ddafit {
namespace {

constexpr double kMaxStrainPerStep = 1e-5;

}  // namespace

void update_block_stress(SubstepContext& ctx, double duration, double relaxation, bool measured) {
  BlockSystem& s = ctx.system;
  const std::vector<ContactManifold>& manifolds = ctx.contacts.manifolds;
  const std::vector<char>& deformable = ctx.deformable;
  if (std::find(deformable.begin(), deformable.end(), char{1}) == deformable.end()) return;
  // Sum of the contact forces' first moments per block: the strain rows of T(p)^T f,
  // (X f_x, Y f_y, (Y f_x + X f_y) / 2) with (X, Y) the point about the centroid.
  const auto first_moment = [](const Vec2& r, const Vec2& f) {
    return Vec3(r.x() * f.x(), r.y() * f.y(), 0.5 * (r.y() * f.x() + r.x() * f.y()));
  };
  std::vector<Vec3> moment(s.blocks.size(), Vec3::Zero());
  for (const ContactManifold& m : manifolds) {
    for (int q = 0; q < m.point_count; ++q) {
      const ContactPoint& p = m.points[q];
      const Vec2 impulse = p.impulse.step_normal * m.normal + p.impulse.step_tangent * m.tangent;  // on block b; -impulse on a
      moment[m.block_b] += first_moment(p.rb, impulse);
      moment[m.block_a] -= first_moment(p.ra, impulse);
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
    // An impact's impulse read as a mean stress gives strains of percent; rock blocks in
    // a slide strain less than 1e-3 in all, so no step may add more than this.
    const double largest = d.segment<3>(3).cwiseAbs().maxCoeff();
    if (largest > kMaxStrainPerStep) d.segment<3>(3) *= kMaxStrainPerStep / largest;
    displace_block(s, static_cast<int>(b), d, measured);
  }
}

}  // namespace ddafit
