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

    // Straight vertices would give zero-area ears and zero-length diagonals; take them
    // out one at a time (each test against the current neighbours, so a short edge at a
    // real corner is not swallowed with its neighbour) and put them back at the end.
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

    std::vector<std::vector<int>> pieces = triangulate(chain);
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
