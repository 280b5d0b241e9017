#include "forward/step/settle_contacts.hpp"

#include <algorithm>

#include "forward/contact_geometry.hpp"

namespace ddafit {

bool settle_contacts(BlockSystem& s, std::vector<Contact>& contacts, const StepParameters& step, int passes,
                     double max_shift, SparseSolver& solver) {
  StepParameters relaxed = step;
  relaxed.time_step *= kSettleStepScale;
  std::vector<char> touching(s.blocks.size(), 0);
  for (const Contact& c : contacts)
    if (c.state != ContactState::Open) touching[c.block_i] = touching[c.block_j] = 1;

  std::vector<Vec6> velocities(s.blocks.size());
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    velocities[b] = s.blocks[b].velocity;
    s.blocks[b].velocity.setZero();
  }
  BlockSparseMatrix k;
  Eigen::VectorXd f, d;
  bool ok = true;
  for (int pass = 0; pass < passes && ok; ++pass) {
    assemble(s, contacts, relaxed, k, f);
    std::string reason;
    ok = solver.solve(k, f, d, reason);
    if (!ok) break;
    double largest = 0.0;
    for (size_t b = 0; b < s.blocks.size(); ++b) {
      const Block& block = s.blocks[b];
      if (block.unknown < 0 || !touching[b]) continue;
      const Vec6 db = d.segment<6>(6 * block.unknown);
      for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v)
        largest = std::max(largest, exact_point_displacement(s.vertices[v], block.centroid, db).norm());
    }
    if (largest > max_shift) break;
    const bool converged = largest <= kSettleTolerance * max_shift;
    for (size_t b = 0; b < s.blocks.size(); ++b) {
      Block& block = s.blocks[b];
      if (block.unknown < 0 || !touching[b]) continue;
      const Vec6 db = d.segment<6>(6 * block.unknown);
      for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v)
        s.vertices[v] += exact_point_displacement(s.vertices[v], block.centroid, db);
      for (MaterialPoint& p : s.points)
        if (p.block == static_cast<int>(b)) {
          const Vec2 shift = exact_point_displacement(p.position, block.centroid, db);
          p.position += shift;
          p.initial_position += shift;  // settling is not part of the measured motion
        }
      block.stress += s.elastic[block.material] * db.segment<3>(3);
      refresh_block_geometry(s, static_cast<int>(b));
    }
    if (converged) break;
  }
  for (size_t b = 0; b < s.blocks.size(); ++b) s.blocks[b].velocity = velocities[b];
  // The contacts now carry the static load; their springs start from here.
  for (Contact& c : contacts) {
    const ContactLinearization lin = linearize_contact(s, c);
    c.normal_gap = lin.area0 / lin.edge_length;
    c.normal_force = c.state == ContactState::Open ? 0.0 : std::max(0.0, -step.penalty * c.normal_gap);
  }
  return ok;
}

}  // namespace ddafit
