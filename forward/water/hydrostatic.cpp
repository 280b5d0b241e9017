#include "forward/water/hydrostatic.hpp"

#include <algorithm>
#include <cmath>

#include "forward/geometry.hpp"

namespace ddafit {
namespace {

// Two-point Gauss-Legendre on [0, 1]: exact for cubics, so for p T (quadratic along a piece)
// and for the potential's p^2 (quadratic).
constexpr double kGaussA = 0.5 - 0.28867513459481287, kGaussB = 0.5 + 0.28867513459481287;

// Calls piece(t0, t1) for every piece of the face P -> Q (parameter t in [0, 1]) that lies
// below the surface, cut where the surface bends (a table point) and where it crosses the
// face, so that the depth z_w - y is linear and >= 0 along each piece.
template <class Piece>
void for_each_wet_piece(const Water& water, const Vec2& p, const Vec2& q, Piece&& piece) {
  const auto depth = [&](double t) {
    const Vec2 x = p + t * (q - p);
    return water_surface(water, x.x()) - x.y();
  };
  // One stretch of the face over which the surface is straight: its wet part.
  const auto stretch = [&](double t0, double t1) {
    if (t1 <= t0) return;
    const double d0 = depth(t0), d1 = depth(t1);
    if (d0 <= 0.0 && d1 <= 0.0) return;
    if (d0 < 0.0) t0 += (t1 - t0) * d0 / (d0 - d1);  // enters the water
    if (d1 < 0.0) t1 = t0 + (t1 - t0) * d0 / (d0 - d1);
    piece(t0, t1);
  };
  const double dx = q.x() - p.x();
  if (water.table.empty() || dx == 0.0) {
    stretch(0.0, 1.0);  // a level surface (the usual reservoir): no cuts, no allocation
    return;
  }
  std::vector<double> cuts{0.0, 1.0};
  for (const Vec2& t : water.table) {
    const double s = (t.x() - p.x()) / dx;
    if (s > 0.0 && s < 1.0) cuts.push_back(s);
  }
  std::sort(cuts.begin(), cuts.end());
  for (size_t k = 0; k + 1 < cuts.size(); ++k) stretch(cuts[k], cuts[k + 1]);
}

}  // namespace

double water_surface(const Water& water, double x) {
  const double z = water.table.empty() ? -INFINITY : polyline_height(water.table, x);
  return water.level ? std::max(z, *water.level) : z;
}

Vec6 water_load(const BlockSystem& s, int b, double gravity, const Vec3& ahead) {
  Vec6 load = Vec6::Zero();
  const Block& block = s.blocks[b];
  const double rho_g = s.water.density * gravity;
  const Vec2 centroid = block.centroid + ahead.head<2>();
  const double c = std::cos(ahead[2]), sn = std::sin(ahead[2]);
  const auto moved = [&](int k) {
    const Vec2 r = s.vertices[block.first_vertex + k % block.vertex_count] - block.centroid;
    return Vec2(centroid.x() + c * r.x() - sn * r.y(), centroid.y() + sn * r.x() + c * r.y());
  };
  for (int k = 0; k < block.vertex_count; ++k) {
    const Vec2 p = moved(k), q = moved(k + 1);
    // Outward normal times the face's length of a counter-clockwise polygon.
    const Vec2 normal_length(q.y() - p.y(), p.x() - q.x());
    for_each_wet_piece(s.water, p, q, [&](double t0, double t1) {
      for (const double g : {kGaussA, kGaussB}) {
        const Vec2 x = p + (t0 + g * (t1 - t0)) * (q - p);
        const double pressure = rho_g * std::max(water_surface(s.water, x.x()) - x.y(), 0.0);
        load += displacement_matrix_transpose_times(x, centroid, -0.5 * (t1 - t0) * pressure * normal_length);
      }
    });
  }
  return load;
}

double water_potential(const BlockSystem& s, double gravity) {
  if (!s.water.present()) return 0.0;
  // ∫_B p dA = ∮ Q n_y ds with Q = -rho_w g (z_w - y)^2 / 2 (dQ/dy = p; Q = 0 above the
  // surface), by the divergence theorem.
  const double rho_g = s.water.density * gravity;
  double u = 0.0;
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    const Block& block = s.blocks[b];
    if (block.fixed) continue;
    for (int k = 0; k < block.vertex_count; ++k) {
      const Vec2& p = s.vertices[block.first_vertex + k];
      const Vec2& q = s.vertices[block.first_vertex + (k + 1) % block.vertex_count];
      const double ny_length = p.x() - q.x();
      for_each_wet_piece(s.water, p, q, [&](double t0, double t1) {
        for (const double g : {kGaussA, kGaussB}) {
          const Vec2 x = p + (t0 + g * (t1 - t0)) * (q - p);
          const double depth = std::max(water_surface(s.water, x.x()) - x.y(), 0.0);
          u += 0.5 * (t1 - t0) * (-0.5 * rho_g * depth * depth) * ny_length;
        }
      });
    }
  }
  return u;
}

}  // namespace ddafit
