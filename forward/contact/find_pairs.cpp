#include "forward/contact/find_pairs.hpp"

#include <omp.h>

#include <algorithm>
#include <limits>
#include <span>

#include "forward/contact/convex_pieces.hpp"
#include "forward/contact/ground_joints.hpp"
#include "forward/geometry.hpp"
#include "forward/kinematics.hpp"
#include "forward/parallel.hpp"

namespace ddafit {

namespace {

// The polygon (counter-clockwise) turns clockwise at vertex k by more than kReflexSine (the
// sine of the turn): a reflex corner. A vertex the mesher left a fraction of a millimetre off
// a straight side (sines of 1e-4 on 8 m Vajont blocks) is no corner at all.
constexpr double kReflexSine = 1e-3;
bool reflex_corner(const std::vector<Vec2>& polygon, int k) {
  const int n = static_cast<int>(polygon.size());
  const Vec2 in = polygon[k] - polygon[(k + n - 1) % n], out = polygon[(k + 1) % n] - polygon[k];
  return turns_inward(in, out, kReflexSine);
}


}  // namespace

std::string build_shapes(const BlockSystem& s, ContactShapes& shapes) {
  shapes = {};
  const GroundJoints joints = find_ground_joints(s, kReflexSine);
  std::vector<Vec2> polygon;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const Block& block = s.blocks[b];
    polygon.assign(s.vertices.begin() + block.first_vertex,
                   s.vertices.begin() + block.first_vertex + block.vertex_count);
    const std::vector<std::vector<int>> pieces = convex_pieces(polygon);
    if (pieces.empty()) return s.block_names[b];
    for (const std::vector<int>& piece : pieces) {
      std::vector<Vec2> corners;
      for (const int k : piece) corners.push_back(polygon[k]);
      shapes.pieces.push_back(
          {b, static_cast<int>(shapes.corners.size()), static_cast<int>(piece.size()), least_width(corners)});
      for (size_t k = 0; k < piece.size(); ++k) {
        const int corner = block.first_vertex + piece[k];
        const int next = block.first_vertex + piece[(k + 1) % piece.size()];
        shapes.corners.push_back(corner);
        // A joint of the fixed ground is no face (ground_joints.hpp); at a corner it ends, the
        // ground's boundary, not the block's, says whether the corner is reflex.
        shapes.solid.push_back(s.next_vertex(corner) == next && !joints.covered[corner] ? 1 : 0);
        const bool reflex = joints.shared[corner] ? joints.reflex[corner] : reflex_corner(polygon, piece[k]);
        shapes.reflex.push_back(reflex ? 1 : 0);
      }
    }
  }
  return {};
}

std::vector<std::pair<int, int>> find_pairs(const BlockSystem& s, const ContactShapes& shapes, double margin,
                                            std::span<const double> extra_reach) {
  struct Box {
    double lo_x, hi_x, lo_y, hi_y;
    int piece;
  };
  const int pieces = static_cast<int>(shapes.pieces.size());
  std::vector<Box> boxes(shapes.pieces.size());
#pragma omp parallel for schedule(static) if (pieces >= kParallelMinimum)
  for (int p = 0; p < pieces; ++p) {
    const ConvexPiece& piece = shapes.pieces[p];
    Box box{1e300, -1e300, 1e300, -1e300, p};
    for (int k = piece.first; k < piece.first + piece.count; ++k) {
      const Vec2& v = s.vertices[shapes.corners[k]];
      box.lo_x = std::min(box.lo_x, v.x());
      box.hi_x = std::max(box.hi_x, v.x());
      box.lo_y = std::min(box.lo_y, v.y());
      box.hi_y = std::max(box.hi_y, v.y());
    }
    if (!extra_reach.empty()) {
      const double grow = extra_reach[piece.block];
      box.lo_x -= grow;
      box.hi_x += grow;
      box.lo_y -= grow;
      box.hi_y += grow;
    }
    boxes[p] = box;
  }
  std::sort(boxes.begin(), boxes.end(), [](const Box& a, const Box& b) { return a.lo_x < b.lo_x; });
  // The sweep over x, in parallel: each thread sweeps from its own share of the boxes and
  // keeps its pairs; the sort below puts them in one order whatever the thread count.
  std::vector<std::vector<std::pair<int, int>>> found(static_cast<size_t>(omp_get_max_threads()));
  const long n = static_cast<long>(boxes.size());
#pragma omp parallel if (n >= kParallelMinimum)
  {
    std::vector<std::pair<int, int>>& mine = found[static_cast<size_t>(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 256)
    for (long i = 0; i < n; ++i) {
      const Box& a = boxes[i];
      const ConvexPiece& pa = shapes.pieces[a.piece];
      for (long j = i + 1; j < n && boxes[j].lo_x <= a.hi_x + margin; ++j) {
        const Box& b = boxes[j];
        if (b.lo_y > a.hi_y + margin || a.lo_y > b.hi_y + margin) continue;
        const ConvexPiece& pb = shapes.pieces[b.piece];
        if (pa.block == pb.block) continue;
        if (s.blocks[pa.block].fixed && s.blocks[pb.block].fixed) continue;
        mine.emplace_back(std::min(a.piece, b.piece), std::max(a.piece, b.piece));
      }
    }
  }
  std::vector<std::pair<int, int>> pairs;
  for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
  // Sorted by (a, b): a counting sort on a, then each (short) run by b. A comparison sort
  // of the ~30 000 pairs of Vajont section VII was 5 % of a run.
  std::vector<int> start(shapes.pieces.size() + 1, 0);
  for (const auto& [a, b] : pairs) ++start[a + 1];
  for (size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
  std::vector<std::pair<int, int>> sorted(pairs.size());
  std::vector<int> next(start.begin(), start.end() - 1);
  for (const auto& pair : pairs) sorted[next[pair.first]++] = pair;
  for (size_t a = 0; a + 1 < start.size(); ++a)
    std::sort(sorted.begin() + start[a], sorted.begin() + start[a + 1]);
  return sorted;
}

}  // namespace ddafit
