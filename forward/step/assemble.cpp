#include "forward/step/assemble.hpp"

#include <cmath>

#include "forward/mass_matrix.hpp"
#include "forward/step/point_springs.hpp"
#include "forward/water/hydrostatic.hpp"

namespace ddafit {
namespace {

void assemble_blocks(const BlockSystem& s, const StepParameters& step, BlockSparseMatrix& k,
                     Eigen::VectorXd& f) {
  const double dt = step.time_step;
  const double g = step.gravity.norm();
  for (int bid = 0; bid < static_cast<int>(s.blocks.size()); ++bid) {
    const Block& b = s.blocks[bid];
    if (b.unknown < 0) continue;
    const double rho = s.density[b.material];
    const Mat6 m = rho * unit_mass_matrix(b);
    // Constant acceleration over the step: (2/dt^2) M D = (2/dt) M V0 + forces.
    Mat6 kb = (2.0 / (dt * dt)) * m;
    kb.block<3, 3>(3, 3) += b.area * s.elastic[b.material];
    k.add(b.unknown, b.unknown, kb);
    k.block_terms.push_back(kb);
    auto fb = f.segment<6>(6 * b.unknown);
    fb += (2.0 / dt) * m * b.velocity;
    fb.segment<3>(3) -= b.area * b.stress;
    fb[0] += rho * b.area * (step.gravity.x() - step.ground_acceleration.x());
    fb[1] += rho * b.area * (step.gravity.y() - step.ground_acceleration.y());
    // The water's force and moment half a step ahead (hydrostatic.hpp). Not its strain
    // terms: the pressure's own squeeze of a block (p/E ~ 1e-5) is nothing to the slide, and
    // applied to the strain unknowns, which start each run unloaded, it set every wet
    // block ringing in its first step, its contacts losing their friction for that step.
    if (s.water.present()) fb.head<3>() += water_load(s, bid, g, 0.5 * dt * b.velocity.head<3>()).head<3>();
  }
}

// Adds the spring energy (stiffness/2) (c0 + a.Di + b.Dj)^2 to the system, and records its
// stiffness term under `key` (SpringTerm). `pair`: the two blocks' index in k.pairs, when both are free.
void add_spring(const Block& bi, const Block& bj, const Vec6& a, const Vec6& b, double c0, double stiffness,
                std::uint64_t key, int pair, BlockSparseMatrix& k, Eigen::VectorXd& f) {
  const int ui = bi.unknown, uj = bj.unknown;
  k.springs.push_back({key, ui, uj, stiffness, ui >= 0 ? a : Vec6::Zero(), uj >= 0 ? b : Vec6::Zero()});
  if (ui >= 0) {
    k.add(ui, ui, stiffness * a * a.transpose());
    f.segment<6>(6 * ui) -= stiffness * c0 * a;
  }
  if (uj >= 0) {
    k.add(uj, uj, stiffness * b * b.transpose());
    f.segment<6>(6 * uj) -= stiffness * c0 * b;
  }
  if (pair >= 0) k.add_to_pair(pair, ui < uj, stiffness * a * b.transpose());
}

}  // namespace

void assemble(const BlockSystem& s, const ContactSet& contacts, const StepParameters& step, GlobalSystem& equations) {
  BlockSparseMatrix& k = equations.k;
  Eigen::VectorXd& f = equations.f;
  k.reset(s.free_block_count);
  f.setZero(6 * s.free_block_count);
  assemble_blocks(s, step, k, f);
  for (size_t mi = 0; mi < contacts.manifolds.size(); ++mi) {
    const ContactManifold& m = contacts.manifolds[mi];
    const Block& ba = s.blocks[m.block_a];
    const Block& bb = s.blocks[m.block_b];
    // Keep the pair in the sparsity pattern even while its points are open, so that
    // contacts opening and closing during the open-close iteration do not force a new
    // symbolic analysis.
    const int pair = ba.unknown >= 0 && bb.unknown >= 0 ? k.pair(ba.unknown, bb.unknown) : -1;
    for (int q = 0; q < m.point_count; ++q) {
      const ContactPoint& p = m.points[q];
      if (p.spring.state == ContactState::Open) {
        // Open at the tension cut-off while still bonded: the bond pulls with its strength,
        // T_s l_c, until it has opened by the slop (contact_law.hpp, wear_bond), as a sliding
        // bonded point resists with tan(phi) N + c l_c. Dropped at once, the elastic springs'
        // most stretched point let go first and a column bonded across joints 0.2 m apart by
        // 1.5 times the strength that holds it toppled bond by bond.
        const double tension = tensile_capacity(s.interfaces[m.interface], p);
        if (tension > 0.0) {
          const PointSprings lin = point_springs(s, m, p);
          if (ba.unknown >= 0) f.segment<6>(6 * ba.unknown) -= tension * lin.normal_a;
          if (bb.unknown >= 0) f.segment<6>(6 * bb.unknown) -= tension * lin.normal_b;
        }
        continue;
      }
      const PointSprings lin = point_springs(s, m, p);
      const std::uint64_t key = 4 * static_cast<std::uint64_t>(mi) + 2 * q;  // + 1 for the shear spring
      // Normal spring (p/2) (d_n - reference)^2, unloaded at spring_reference() (assemble.hpp).
      add_spring(ba, bb, lin.normal_a, lin.normal_b, lin.gap0 - spring_reference(p, step), step.penalty, key, pair, k,
                 f);
      if (p.spring.state == ContactState::Locked) {
        add_spring(ba, bb, lin.shear_a, lin.shear_b, p.spring.shear_offset, locked_shear_stiffness(p.spring, step),
                   key + 1, pair, k, f);
      } else {
        // Sliding: a known friction force opposing the slip of b relative to a.
        const double force = p.spring.slip_direction * sliding_friction_force(s.interfaces[m.interface], m, p);
        if (ba.unknown >= 0) f.segment<6>(6 * ba.unknown) -= force * lin.shear_a;
        if (bb.unknown >= 0) f.segment<6>(6 * bb.unknown) -= force * lin.shear_b;
      }
    }
  }
}

}  // namespace ddafit
