#include "forward/contact/laws/thermal_pressurization.hpp"

#include <algorithm>
#include <cmath>

namespace ddafit::laws {
namespace {

constexpr int kBandCells = 8;            // across the half band
constexpr double kGrowth = 1.05;         // thickness ratio of neighbouring cells outside it
constexpr double kDiffusionLengths = 6;  // depth of the grid in sqrt(alpha t) of the run
constexpr int kMaxCells = 600;

// Backward Euler for w_k (u_k' - u_k) = dt alpha [flux in - flux out] + w_k source_k, with no
// flux at the mid-plane and u = 0 at the far boundary: a tridiagonal system (Thomas).
void diffuse(const DiffusionGrid& g, double alpha, double dt, const std::vector<double>& rhs, double* u) {
  const size_t n = g.width.size();
  if (alpha == 0.0) {
    for (size_t k = 0; k < n; ++k) u[k] = rhs[k] / g.width[k];
    return;
  }
  std::vector<double> c(n), d(n);
  double previous_upper = 0.0, previous_d = 0.0;
  for (size_t k = 0; k < n; ++k) {
    const double lower = k > 0 ? -dt * alpha / g.gap[k - 1] : 0.0;
    const double upper = -dt * alpha / g.gap[k];  // the last: towards the far boundary (u = 0)
    const double diagonal = g.width[k] - lower - upper;
    const double pivot = diagonal - lower * previous_upper;
    c[k] = k + 1 < n ? upper / pivot : 0.0;
    d[k] = (rhs[k] - lower * previous_d) / pivot;
    previous_upper = c[k];
    previous_d = d[k];
  }
  u[n - 1] = d[n - 1];
  for (size_t k = n - 1; k-- > 0;) u[k] = d[k] - c[k] * u[k + 1];
}

}  // namespace

DiffusionGrid make_diffusion_grid(const Interface& face, double duration) {
  DiffusionGrid g;
  const double half = 0.5 * face.band_thickness;
  const double alpha = std::max(face.thermal_diffusivity, face.hydraulic_diffusivity);
  const double depth = std::max(4.0 * face.band_thickness, kDiffusionLengths * std::sqrt(alpha * duration));
  g.band_cells = kBandCells;
  double width = half / kBandCells, reached = 0.0;
  for (int k = 0; k < kBandCells; ++k, reached += width) g.width.push_back(width);
  while (reached < depth && static_cast<int>(g.width.size()) < kMaxCells) {
    width *= kGrowth;
    g.width.push_back(width);
    reached += width;
  }
  for (size_t k = 0; k < g.width.size(); ++k)
    g.gap.push_back(k + 1 < g.width.size() ? 0.5 * (g.width[k] + g.width[k + 1]) : 0.5 * g.width[k]);
  return g;
}

void start_column(const DiffusionGrid& grid, std::vector<double>& column) {
  column.assign(2 * grid.width.size(), 0.0);
}

double advance_column(const Interface& face, const DiffusionGrid& g, double heat, double dt,
                      std::vector<double>& column) {
  const size_t n = g.width.size();
  double* temperature = column.data();
  double* pressure = column.data() + n;
  // Temperature: the heat spread over the band (rho c h per kelvin and m^2), then diffusion.
  const double rise = heat / (face.heat_capacity * face.band_thickness);
  std::vector<double> rhs(n), before(temperature, temperature + n);
  for (size_t k = 0; k < n; ++k)
    rhs[k] = g.width[k] * (temperature[k] + (static_cast<int>(k) < g.band_cells ? rise : 0.0));
  diffuse(g, face.thermal_diffusivity, dt, rhs, temperature);
  // Pore pressure: Lambda times the temperature change of the step, then diffusion.
  for (size_t k = 0; k < n; ++k)
    rhs[k] = g.width[k] * (pressure[k] + face.pressurization_factor * (temperature[k] - before[k]));
  diffuse(g, face.hydraulic_diffusivity, dt, rhs, pressure);
  double band = 0.0, thickness = 0.0;
  for (int k = 0; k < g.band_cells; ++k) {
    band += g.width[k] * pressure[k];
    thickness += g.width[k];
  }
  return band / thickness;
}

}  // namespace ddafit::laws
