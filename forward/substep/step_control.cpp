#include "forward/substep/step_control.hpp"

#include <algorithm>
#include <cmath>

#include "forward/substep/substep_types.hpp"

namespace ddafit {
namespace {

// Largest distance from a block's centroid to one of its vertices, m.
double block_reach(const BlockSystem& s, int b) {
  const Block& block = s.blocks[b];
  double r = 0.0;
  for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v)
    r = std::max(r, (s.vertices[v] - block.centroid).norm());
  return r;
}

}  // namespace

// The next step: the scene's, grown back by the growth factor after a shorter one, and
// short enough that no vertex of a block in contact moves further than allowed, counting
// the speed gravity adds within the step (the contact margin covers that distance). A
// block in flight does not shorten the step: its flight is exact (trapezoidal update), and
// speculative_reach() widens its contact margin by its travel instead. One small block
// thrown clear of section VII's toe at 50 m/s had cut every step of the slide to 3 ms. With
// control.step_by_turn, a block in contact limits the step only by the travel its turning gives
// its vertices; its sliding travel beyond the limit widens its margin as a flight's does.
double choose_step(SubstepContext& w, double previous) {
  const BlockSystem& s = w.system;
  const Scene& scene = w.scene;
  const double max_move = w.max_move;
  double fastest = 0.0;
  const bool by_turn = scene.options.step_by_turn;  // the vertices' turning only (options.hpp)
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    if (s.blocks[b].fixed) continue;
    w.reach[b] = block_reach(s, static_cast<int>(b));
    if (!w.near[b]) continue;
    const Block& block = s.blocks[b];
    const double speed = by_turn ? turn_speed_bound(block, w.reach[b]) : vertex_speed_bound(block, w.reach[b]);
    fastest = std::max(fastest, speed);
  }
  const double g = scene.gravity.norm() + w.ground.peak_acceleration();
  // (fastest + g dt) dt <= max_move
  const double limit = g > 0.0 ? (-fastest + std::sqrt(fastest * fastest + 4.0 * g * max_move)) / (2.0 * g)
                               : max_move / std::max(fastest, 1e-300);
  const double step = std::min({scene.max_step, previous * scene.options.step_growth_factor, limit});
  return std::max(step, scene.options.min_step_ratio * scene.max_step);
}

// Per block, how much further than max_move its vertices can travel in a step of dt: the
// speculative margin its contacts get on top of the scene's (zero for blocks in contact,
// whose speed chose the step, unless control.step_by_turn). Gravity's share
// counted as in choose_step.
void speculative_reach(SubstepContext& w, double dt) {
  const BlockSystem& s = w.system;
  const double gravity = w.scene.gravity.norm() + w.ground.peak_acceleration();
  const double max_move = w.max_move;
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    const double travel = s.blocks[b].fixed ? 0.0 : (vertex_speed_bound(s.blocks[b], w.reach[b]) + gravity * dt) * dt;
    w.extra_reach[b] = std::max(0.0, travel - max_move);
  }
}

// Which blocks have a contact point within `margin` (the scene's margin, not the widened one).
void mark_near(SubstepContext& w) {
  const double margin = w.detection.settings.margin;
  std::vector<char>& near = w.near;
  std::fill(near.begin(), near.end(), 0);
  for (const ContactManifold& m : w.contacts.manifolds)
    for (int q = 0; q < m.point_count; ++q)
      if (m.points[q].separation < margin) near[m.block_a] = near[m.block_b] = 1;
}

// Largest distance a vertex of a block in contact moved in the step (translation plus
// rotation times reach).
double largest_move(const SubstepContext& w) {
  const BlockSystem& s = w.system;
  double moved = 0.0;
  for (size_t b = 0; b < s.blocks.size(); ++b)
    if (!s.blocks[b].fixed && w.extra_reach[b] == 0.0)
      moved = std::max(moved, w.state.step_moves[b].head<2>().norm() + w.reach[b] * std::abs(w.state.step_moves[b][2]));
  return moved;
}

}  // namespace ddafit
