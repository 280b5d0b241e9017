#include "forward/contact/convex_pieces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace ddafit {
namespace {

// Distance below which a vertex counts as lying on the line through its neighbours,
// relative to the polygon's size. Round-off on coordinates of ~3000 m is ~1e-12 m, so
// 1e-9 of a block's size is far above the noise yet far below any real corner.
constexpr double kFlatTolerance = 1e-9;

// Twice the signed area of (a, b, c): > 0 when c lies left of a -> b (a left turn at b).
double turn(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

class Decomposer {
 public:
  explicit Decomposer(std::span<const Vec2> polygon) {
    // Work relative to the first vertex: coordinates are up to ~3000 m while the
    // blocks are metres across, and differences of small numbers keep more digits.
    p_.reserve(polygon.size());
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec2& v : polygon) {
      p_.push_back(v - polygon[0]);
      lo = lo.cwiseMin(p_.back());
      hi = hi.cwiseMax(p_.back());
    }
    size_ = (hi - lo).maxCoeff();
    flat_ = kFlatTolerance * size_;
  }

  std::vector<std::vector<int>> run() {
    const int n = static_cast<int>(p_.size());
    if (n < 3 || !std::isfinite(size_) || !(size_ > 0.0)) return {};
    double twice_area = 0.0;
    for (int k = 0; k < n; ++k) twice_area += turn(Vec2::Zero(), p_[k], p_[(k + 1) % n]);
    if (!(std::abs(twice_area) > flat_ * size_)) return {};  // thinner than the tolerance

    // Counter-clockwise walk of the input indices (reversed for a clockwise input).
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    if (twice_area < 0.0) std::reverse(order.begin(), order.end());

    // The common case: a convex block is its own single piece, indices untouched.
    bool convex = true;
    for (int k = 0; k < n && convex; ++k)
      convex = !reflex(order[(k + n - 1) % n], order[k], order[(k + 1) % n]);
    if (convex) return {order};

    // Cuts from the reflex corners; straight vertices may end a cut (a notch under a vertex
    // of a straight top is cut to that vertex, not to the top's far corner).
    std::vector<std::vector<int>> pieces;
    if (split(order, pieces)) {
      merge(pieces);
      return pieces;
    }

    // Only round-off on a nearly degenerate polygon hides every cut from a reflex corner:
    // clip ears instead. Straight vertices would give zero-area ears and zero-length
    // diagonals; take them out one at a time (each test against the current neighbours, so
    // a short edge at a real corner is not swallowed with its neighbour) and put them back
    // at the end.
    std::vector<int> chain = order;
    for (bool removed = true; removed && chain.size() > 3;) {
      removed = false;
      for (size_t k = 0; k < chain.size() && chain.size() > 3;) {
        const size_t m = chain.size();
        if (straight(chain[(k + m - 1) % m], chain[k], chain[(k + 1) % m])) {
          chain.erase(chain.begin() + static_cast<long>(k));
          removed = true;
        } else {
          ++k;
        }
      }
    }
    double chain_area = 0.0;
    for (size_t k = 0; k < chain.size(); ++k)
      chain_area += turn(Vec2::Zero(), p_[chain[k]], p_[chain[(k + 1) % chain.size()]]);
    if (chain.size() < 3 || !(chain_area > flat_ * size_)) return {};

    pieces = triangulate(chain);
    merge(pieces);
    return restore_straight(pieces, order, chain);
  }

 private:
  // Distance of b from the line a-c, signed positive for a left turn, compared with the
  // tolerance times |c - a| so that no square root or division is needed.
  bool reflex(int a, int b, int c) const {
    return turn(p_[a], p_[b], p_[c]) < -flat_ * (p_[c] - p_[a]).norm();
  }
  bool straight(int a, int b, int c) const {
    return std::abs(turn(p_[a], p_[b], p_[c])) <= flat_ * (p_[c] - p_[a]).norm();
  }

  // Interior angle at x of a counter-clockwise walk prev -> x -> next, in [0, 2 pi).
  double interior(int prev, int x, int next) const {
    const Vec2 u = p_[next] - p_[x], w = p_[prev] - p_[x];
    const double a = std::atan2(u.x() * w.y() - u.y() * w.x(), u.dot(w));
    return a < 0.0 ? a + 2.0 * M_PI : a;
  }

  // Whether segment r-v touches the edge q0-q1 (closed: touching counts).
  bool touches(int r, int v, int q0, int q1) const {
    const double t0 = turn(p_[r], p_[v], p_[q0]), t1 = turn(p_[r], p_[v], p_[q1]);
    const double t2 = turn(p_[q0], p_[q1], p_[r]), t3 = turn(p_[q0], p_[q1], p_[v]);
    if ((t0 > 0.0 && t1 > 0.0) || (t0 < 0.0 && t1 < 0.0) || (t2 > 0.0 && t3 > 0.0) || (t2 < 0.0 && t3 < 0.0))
      return false;
    const Vec2 lo = p_[r].cwiseMin(p_[v]), hi = p_[r].cwiseMax(p_[v]);  // collinear: boxes must meet
    const Vec2 qlo = p_[q0].cwiseMin(p_[q1]), qhi = p_[q0].cwiseMax(p_[q1]);
    return (lo.array() <= qhi.array()).all() && (qlo.array() <= hi.array()).all();
  }

  // Splits a counter-clockwise walk at diagonals from its reflex corners until every piece
  // is convex. Each cut runs from the most reflex corner to the vertex that leaves the
  // largest smallest angle at the cut's two ends, preferring cuts that leave that corner
  // convex on both sides. Hertel-Mehlhorn on an ear-clipping triangulation picks its cuts
  // by the order of the ears instead, and on Vajont section X it cut a block along its top
  // face from a notch 3 cm below it: an 8 m piece 3 cm thick whose only solid face was that
  // top, so a block whose tip sat in the notch read itself 4 cm deep in it, was pushed into
  // the block's other piece and overlapped it by 3 % of its size (model revision 2026-12-07.3).
  bool split(const std::vector<int>& c, std::vector<std::vector<int>>& pieces) const {
    const size_t m = c.size();
    std::vector<std::pair<double, size_t>> corners;  // (interior angle, position), reflex only
    for (size_t i = 0; i < m; ++i)
      if (reflex(c[(i + m - 1) % m], c[i], c[(i + 1) % m]))
        corners.push_back({interior(c[(i + m - 1) % m], c[i], c[(i + 1) % m]), i});
    if (corners.empty()) {
      pieces.push_back(c);
      return true;
    }
    std::sort(corners.rbegin(), corners.rend());
    for (const auto& [angle_r, i] : corners) {
      const int r = c[i], r_prev = c[(i + m - 1) % m], r_next = c[(i + 1) % m];
      double best_score = -1.0;
      size_t best = m;
      for (size_t j = 0; j < m; ++j) {
        if (j == i || j == (i + 1) % m || (j + 1) % m == i) continue;
        const int v = c[j], v_prev = c[(j + m - 1) % m], v_next = c[(j + 1) % m];
        const double r1 = interior(v, r, r_next), r2 = interior(r_prev, r, v);
        const double v1 = interior(v_prev, v, r), v2 = interior(r, v, v_next);
        // Inside both corners' cones: the two parts of each corner add up to the whole.
        const double angle_v = interior(v_prev, v, v_next);
        if (!(r1 > 0.0 && r2 > 0.0 && std::abs(r1 + r2 - angle_r) < 1e-9)) continue;
        if (!(v1 > 0.0 && v2 > 0.0 && std::abs(v1 + v2 - angle_v) < 1e-9)) continue;
        bool clear = true;
        for (size_t k = 0; k < m && clear; ++k) {
          const int q0 = c[k], q1 = c[(k + 1) % m];
          if (q0 != r && q1 != r && q0 != v && q1 != v) clear = !touches(r, v, q0, q1);
        }
        if (!clear) continue;
        const bool resolves = r1 <= M_PI && r2 <= M_PI;
        const double score = std::min({r1, r2, v1, v2}) * (resolves ? 1.0 : 0.5);
        if (score > best_score) best_score = score, best = j;
      }
      if (best == m) continue;  // no cut from this corner (round-off): try the next one
      std::vector<int> one, two;
      for (size_t k = i;; k = (k + 1) % m) {
        one.push_back(c[k]);
        if (k == best) break;
      }
      for (size_t k = best;; k = (k + 1) % m) {
        two.push_back(c[k]);
        if (k == i) break;
      }
      return split(one, pieces) && split(two, pieces);
    }
    return false;
  }

  // Closed triangle test: a vertex on the would-be diagonal must block the ear too,
  // otherwise the rest of the polygon would touch itself there.
  bool in_triangle(int a, int b, int c, int q) const {
    return turn(p_[a], p_[b], p_[q]) >= 0.0 && turn(p_[b], p_[c], p_[q]) >= 0.0 &&
           turn(p_[c], p_[a], p_[q]) >= 0.0;
  }

  // Ear clipping. Of all valid ears the fattest (area over longest side squared) is cut
  // first, so slivers are left to the end, where few remain; O(n^3), fine for n < 100.
  std::vector<std::vector<int>> triangulate(std::vector<int> rest) const {
    std::vector<std::vector<int>> triangles;
    while (rest.size() > 3) {
      const size_t m = rest.size();
      long best = -1, fallback = -1;
      double best_quality = -1.0, fallback_quality = -1.0;
      for (size_t k = 0; k < m; ++k) {
        const int a = rest[(k + m - 1) % m], b = rest[k], c = rest[(k + 1) % m];
        const double t = turn(p_[a], p_[b], p_[c]);
        if (!(t > 0.0)) continue;
        const double longest = std::max({(p_[b] - p_[a]).squaredNorm(),
                                         (p_[c] - p_[b]).squaredNorm(),
                                         (p_[a] - p_[c]).squaredNorm()});
        const double quality = t / longest;
        if (quality > fallback_quality) {
          fallback_quality = quality;
          fallback = static_cast<long>(k);
        }
        bool empty = true;
        for (size_t j = 0; j < m && empty; ++j) {
          const int q = rest[j];
          if (q != a && q != b && q != c && in_triangle(a, b, c, q)) empty = false;
        }
        if (empty && quality > best_quality) {
          best_quality = quality;
          best = static_cast<long>(k);
        }
      }
      // A simple polygon always has an ear; only round-off on a nearly degenerate input
      // can hide them all. Cutting the fattest convex corner anyway still tiles exactly.
      if (best < 0) best = fallback >= 0 ? fallback : 0;
      const size_t k = static_cast<size_t>(best);
      triangles.push_back({rest[(k + m - 1) % m], rest[k], rest[(k + 1) % m]});
      rest.erase(rest.begin() + best);
    }
    triangles.push_back(rest);
    return triangles;
  }

  // Hertel-Mehlhorn: drop every diagonal whose two ends stay convex once the two pieces
  // beside it are joined. Each piece is convex, so only those two corners can turn reflex.
  void merge(std::vector<std::vector<int>>& pieces) const {
    for (bool merged = true; merged;) {
      merged = false;
      for (size_t i = 0; i < pieces.size() && !merged; ++i) {
        for (size_t j = i + 1; j < pieces.size() && !merged; ++j) {
          std::vector<int> joined = join(pieces[i], pieces[j]);
          if (joined.empty()) continue;
          pieces[i] = std::move(joined);
          pieces.erase(pieces.begin() + static_cast<long>(j));
          merged = true;
        }
      }
    }
  }

  // The union of two pieces sharing a diagonal u -> v (v -> u in the other), or empty
  // when they share none or the union would be reflex at u or v.
  std::vector<int> join(const std::vector<int>& a, const std::vector<int>& b) const {
    const size_t na = a.size(), nb = b.size();
    for (size_t i = 0; i < na; ++i) {
      const int u = a[i], v = a[(i + 1) % na];
      for (size_t j = 0; j < nb; ++j) {
        if (b[j] != v || b[(j + 1) % nb] != u) continue;
        // Walk a from v round to u, then b from after u round to before v.
        std::vector<int> out;
        for (size_t k = 0; k < na; ++k) out.push_back(a[(i + 1 + k) % na]);
        for (size_t k = 2; k < nb; ++k) out.push_back(b[(j + k) % nb]);
        const size_t m = out.size(), at_u = na - 1;
        if (reflex(out[at_u - 1], u, out[(at_u + 1) % m]) || reflex(out[m - 1], v, out[1]))
          return {};
        return out;
      }
    }
    return {};
  }

  // Puts each straight vertex back between the two chain vertices around it, in the one
  // piece that has that chain edge on its boundary.
  std::vector<std::vector<int>> restore_straight(const std::vector<std::vector<int>>& pieces,
                                                 const std::vector<int>& order,
                                                 const std::vector<int>& chain) const {
    const int n = static_cast<int>(order.size());
    std::vector<int> position(n), chain_next(n, -1);
    for (int k = 0; k < n; ++k) position[order[k]] = k;
    for (size_t k = 0; k < chain.size(); ++k) chain_next[chain[k]] = chain[(k + 1) % chain.size()];
    std::vector<std::vector<int>> out;
    for (const std::vector<int>& piece : pieces) {
      std::vector<int> full;
      for (size_t k = 0; k < piece.size(); ++k) {
        const int x = piece[k], y = piece[(k + 1) % piece.size()];
        full.push_back(x);
        if (chain_next[x] != y) continue;  // a diagonal: nothing was removed along it
        for (int q = (position[x] + 1) % n; q != position[y]; q = (q + 1) % n)
          full.push_back(order[q]);
      }
      out.push_back(std::move(full));
    }
    return out;
  }

  std::vector<Vec2> p_;
  double size_ = 0.0;
  double flat_ = 0.0;
};

}  // namespace

std::vector<std::vector<int>> convex_pieces(std::span<const Vec2> polygon) {
  return Decomposer(polygon).run();
}

}  // namespace ddafit
