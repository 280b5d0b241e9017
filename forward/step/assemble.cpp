#include "forward/step/assemble.hpp"

#include <cmath>

#include "forward/contact_geometry.hpp"
#include "forward/contact_law.hpp"
#include "forward/mass_matrix.hpp"

namespace ddafit {
namespace {

void assemble_blocks(const BlockSystem& s, const StepParameters& step, BlockSparseMatrix& k,
                     Eigen::VectorXd& f) {
  const double dt = step.time_step;
  for (const Block& b : s.blocks) {
    if (b.unknown < 0) continue;
    const double rho = s.density[b.material];
    const Mat6 m = rho * unit_mass_matrix(b);
    // Constant acceleration over the step: (2/dt^2) M D = (2/dt) M V0 + forces.
    Mat6 kb = (2.0 / (dt * dt)) * m;
    kb.block<3, 3>(3, 3) += b.area * s.elastic[b.material];
    k.add(b.unknown, b.unknown, kb);
    auto fb = f.segment<6>(6 * b.unknown);
    fb += (2.0 / dt) * m * b.velocity;
    fb.segment<3>(3) -= b.area * b.stress;
    fb[0] += rho * b.area * step.gravity.x();
    fb[1] += rho * b.area * step.gravity.y();
  }
}

// Adds the spring energy (stiffness/2) (c0 + a.Di + b.Dj)^2 to the system.
void add_spring(const Block& bi, const Block& bj, const Vec6& a, const Vec6& b, double c0, double stiffness,
                BlockSparseMatrix& k, Eigen::VectorXd& f) {
  const int ui = bi.unknown, uj = bj.unknown;
  if (ui >= 0) {
    k.add(ui, ui, stiffness * a * a.transpose());
    f.segment<6>(6 * ui) -= stiffness * c0 * a;
  }
  if (uj >= 0) {
    k.add(uj, uj, stiffness * b * b.transpose());
    f.segment<6>(6 * uj) -= stiffness * c0 * b;
  }
  if (ui >= 0 && uj >= 0) k.add(ui, uj, stiffness * a * b.transpose());
}

}  // namespace

double sliding_friction_force(const BlockSystem& s, const Contact& c) {
  const Interface& face = s.interfaces[c.interface];
  // The step's own slip would feed back inside the open-close iteration (a trial pass
  // that slips far degrades friction, which lets the next pass slip further); the last
  // accepted step's slip predicts it to second order without that loop.
  const double mid_slip = c.accumulated_slip + 0.5 * c.last_step_slip;
  return c.normal_force * friction_coefficient(face, mid_slip, c.critical_distance);
}

double locked_shear_limit(const BlockSystem& s, const Contact& c) {
  const Interface& face = s.interfaces[c.interface];
  const double mid_slip = c.accumulated_slip + 0.5 * c.last_step_slip;
  return shear_strength(face, c.normal_force, mid_slip, c.critical_distance, c.bonded, c.bond_length);
}

void assemble(const BlockSystem& s, const std::vector<Contact>& contacts, const StepParameters& step,
              BlockSparseMatrix& k, Eigen::VectorXd& f) {
  k.reset(s.free_block_count);
  f.setZero(6 * s.free_block_count);
  assemble_blocks(s, step, k, f);
  for (const Contact& c : contacts) {
    const Block& bi = s.blocks[c.block_i];
    const Block& bj = s.blocks[c.block_j];
    if (c.state == ContactState::Open) {
      // Keep the pair in the sparsity pattern, so that contacts opening and closing
      // during the open-close iteration do not force a new symbolic analysis.
      if (bi.unknown >= 0 && bj.unknown >= 0) k.add(bi.unknown, bj.unknown, Mat6::Zero());
      continue;
    }
    const ContactLinearization lin = linearize_contact(s, c);
    // Normal spring on d_n = A / l: stiffness p / l^2 on A.
    const double l2 = lin.edge_length * lin.edge_length;
    // Shifted so that the spring is unloaded at spring_reference() (assemble.hpp).
    const double area0 = lin.area0 - spring_reference(c, step) * lin.edge_length;
    add_spring(bi, bj, lin.e, lin.g, area0, step.penalty / l2, k, f);
    if (c.state == ContactState::Locked) {
      add_spring(bi, bj, lin.es, lin.gs, lin.shear0, step.shear_penalty, k, f);
    } else {
      // Sliding: a known friction force opposing the slip, at P1 on i and P0 on j.
      const double force = c.slip_direction * sliding_friction_force(s, c);
      if (bi.unknown >= 0) f.segment<6>(6 * bi.unknown) -= force * lin.es;
      if (bj.unknown >= 0) f.segment<6>(6 * bj.unknown) -= force * lin.gs;
    }
  }
}

}  // namespace ddafit
