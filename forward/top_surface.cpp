#include "forward/top_surface.hpp"

#include "forward/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ddafit {

std::vector<Vec2> top_surface(const BlockSystem& s, int columns, SurfaceOf of) {
  if (s.vertices.empty() || columns < 1) return {};
  const auto counted = [&](const Block& b) { return of == SurfaceOf::AllBlocks || b.fixed; };
  double x0 = INFINITY, x1 = -INFINITY;
  for (const Block& b : s.blocks)
    if (counted(b))
      for (int k = 0; k < b.vertex_count; ++k)
        x0 = std::min(x0, s.vertices[b.first_vertex + k].x()), x1 = std::max(x1, s.vertices[b.first_vertex + k].x());
  const double width = (x1 - x0) / columns;
  if (!(width > 0.0)) return {};
  std::vector<double> top(static_cast<size_t>(columns), -INFINITY);
  for (const Block& b : s.blocks) {
    if (!counted(b)) continue;
    for (int k = 0; k < b.vertex_count; ++k) {
      const Vec2& p = s.vertices[b.first_vertex + k];
      const Vec2& q = s.vertices[b.first_vertex + (k + 1) % b.vertex_count];
      const double lo = std::min(p.x(), q.x()), hi = std::max(p.x(), q.x());
      // The columns whose middle x lies on this edge's span.
      const int first = std::max(0, static_cast<int>(std::ceil((lo - x0) / width - 0.5)));
      const int last = std::min(columns - 1, static_cast<int>(std::floor((hi - x0) / width - 0.5)));
      for (int c = first; c <= last; ++c) {
        const double x = x0 + (c + 0.5) * width;
        const double z = hi > lo ? p.y() + (q.y() - p.y()) * (x - p.x()) / (q.x() - p.x()) : std::max(p.y(), q.y());
        top[c] = std::max(top[c], z);
      }
    }
  }
  std::vector<Vec2> out;
  for (int c = 0; c < columns; ++c)
    if (std::isfinite(top[c])) out.emplace_back(x0 + (c + 0.5) * width, top[c]);
  return out;
}

double surface_misfit_rms(const std::vector<Vec2>& surface, const std::vector<Vec2>& reference, double from, double to) {
  double sum = 0.0;
  int n = 0;
  for (const Vec2& p : surface) {
    if (p.x() < from || p.x() > to) continue;
    const double d = p.y() - polyline_height(reference, p.x());
    sum += d * d;
    ++n;
  }
  return n > 0 ? std::sqrt(sum / n) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace ddafit
