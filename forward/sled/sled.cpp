#include "forward/sled/sled.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "forward/common/displace_block.hpp"
#include "forward/contact/friction_law.hpp"
#include "forward/top_surface.hpp"

namespace ddafit {
namespace {

constexpr int kColumns = 2000;  // points of the path over the fixed blocks' width (column middles)
constexpr int kSlices = 200;    // over the free blocks' width: the mass's distribution along the path
constexpr double kPi = 3.14159265358979323846;

// The fixed blocks' top along x (kColumns points) and its arc length.
struct Path {
  std::vector<Vec2> points;
  std::vector<double> arc;

  double length() const { return arc.empty() ? 0.0 : arc.back(); }
  // Index of the segment holding arc length s (clamped to the ends).
  size_t segment(double s) const {
    const size_t k = static_cast<size_t>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin());
    return std::min(std::max<size_t>(k, 1), arc.size() - 1) - 1;
  }
  Vec2 tangent(double s) const {
    const size_t k = segment(s);
    return (points[k + 1] - points[k]).normalized();
  }
  // The point at arc length s; beyond either end, on along the end segment.
  Vec2 at(double s) const {
    const size_t k = segment(s);
    return points[k] + (s - arc[k]) * tangent(s);
  }
  double arc_at(double x) const {
    for (size_t k = 0; k + 1 < points.size(); ++k)
      if (x <= points[k + 1].x() || k + 2 == points.size())
        return arc[k] + (x - points[k].x()) / (points[k + 1].x() - points[k].x()) * (arc[k + 1] - arc[k]);
    return 0.0;
  }
};

// The vertical line at x through block b's polygon: its length inside, and its lowest and
// highest crossing (length 0 when it misses the block).
struct Chord {
  double length = 0.0, lowest = 0.0, highest = 0.0;
};
Chord chord(const BlockSystem& s, int b, double x) {
  const Block& block = s.blocks[b];
  std::vector<double> ys;
  for (int k = 0; k < block.vertex_count; ++k) {
    const Vec2& p = s.vertices[block.first_vertex + k];
    const Vec2& q = s.vertices[block.first_vertex + (k + 1) % block.vertex_count];
    if ((p.x() <= x) == (q.x() <= x)) continue;  // half-open: a vertex on x counts once
    ys.push_back(p.y() + (q.y() - p.y()) * (x - p.x()) / (q.x() - p.x()));
  }
  std::sort(ys.begin(), ys.end());
  Chord c;
  for (size_t k = 0; k + 1 < ys.size(); k += 2) c.length += ys[k + 1] - ys[k];
  if (!ys.empty()) c.lowest = ys.front(), c.highest = ys.back();
  return c;
}

// The path: the fixed blocks' top surface (forward/top_surface.hpp) and its arc length.
Path fixed_top(const BlockSystem& s) {
  Path path;
  path.points = top_surface(s, kColumns, SurfaceOf::FixedBlocks);
  path.arc.assign(path.points.size(), 0.0);
  for (size_t k = 1; k < path.points.size(); ++k) path.arc[k] = path.arc[k - 1] + (path.points[k] - path.points[k - 1]).norm();
  return path;
}

struct Slice {
  double start = 0.0;  // arc length of its base at t = 0
  double mass = 0.0;   // kg per metre of thickness
  int interface = -1;
  double critical_distance = 0.0;
};

struct Sled {
  Path path;
  std::vector<Slice> slices;
  double mass = 0.0;
  std::vector<int> block_slice;  // per block: the slice under its centroid, -1 if fixed
  int unsupported = 0;           // slices with no fixed block or no interface under them: left out
};

Sled build(const Scene& scene, const BlockSystem& s) {
  Sled sled;
  double x0 = INFINITY, x1 = -INFINITY;  // the free blocks' extent: the slices'
  for (const Block& block : s.blocks)
    if (!block.fixed)
      for (int k = 0; k < block.vertex_count; ++k)
        x0 = std::min(x0, s.vertices[block.first_vertex + k].x()), x1 = std::max(x1, s.vertices[block.first_vertex + k].x());
  if (!(x1 > x0)) return sled;
  sled.path = fixed_top(s);
  if (sled.path.points.size() < 2) return sled;
  const double width = (x1 - x0) / kSlices;
  for (int c = 0; c < kSlices; ++c) {
    const double x = x0 + (c + 0.5) * width;
    Slice slice;
    double lowest = INFINITY;
    int lowest_block = -1;
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
      if (s.blocks[b].fixed) continue;
      const Chord c = chord(s, b, x);
      if (c.length <= 0.0) continue;
      slice.mass += s.density[s.blocks[b].material] * c.length * width;
      if (c.lowest < lowest) lowest = c.lowest, lowest_block = b;
    }
    if (lowest_block < 0) continue;
    slice.start = sled.path.arc_at(x);
    // The interface between the lowest free block and the fixed ground under it.
    int below = -1;
    double top = -INFINITY;
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
      if (!s.blocks[b].fixed) continue;
      const Chord c = chord(s, b, x);
      if (c.length > 0.0 && c.highest > top) top = c.highest, below = b;
    }
    slice.interface = below >= 0 ? s.interface_between(lowest_block, below) : -1;
    if (slice.interface < 0) {
      ++sled.unsupported;  // its mass would drive the sled with no friction under it
      continue;
    }
    const double length = scene.mesh.block_size > 0.0 ? scene.mesh.block_size
                                                      : block_length_along(s, lowest_block, sled.path.tangent(slice.start));
    slice.critical_distance = s.interfaces[slice.interface].critical_distance_ratio * length;
    sled.mass += slice.mass;
    sled.slices.push_back(slice);
  }
  sled.block_slice.assign(s.blocks.size(), -1);
  for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
    if (s.blocks[b].fixed || sled.slices.empty()) continue;
    const double at = sled.path.arc_at(s.blocks[b].centroid.x());
    int best = 0;
    for (int k = 1; k < static_cast<int>(sled.slices.size()); ++k)
      if (std::abs(sled.slices[k].start - at) < std::abs(sled.slices[best].start - at)) best = k;
    sled.block_slice[b] = best;
  }
  return sled;
}

// Driving and resisting force (N/m) at displacement u and speed v: gravity's component along
// the path and the friction's cap, sum mu m g cos b.
// u is where the sled is along the path, d the slip its base has accumulated (the law's d,
// seed Eq. 2: the path length travelled, |u'| integrated, never signed).
void forces(const Sled& sled, const BlockSystem& s, double g, double u, double d, double v, double* drive,
            double* resist) {
  *drive = *resist = 0.0;
  for (const Slice& slice : sled.slices) {
    const Vec2 t = sled.path.tangent(slice.start + u);
    const double sin_b = -t.y(), cos_b = t.x();
    const Interface& face = s.interfaces[slice.interface];
    const double mu = friction_law(face, {d, std::abs(v), slice.critical_distance, 0.0, 0.0});
    *drive += slice.mass * g * sin_b;
    *resist += mu * slice.mass * g * std::max(cos_b, 0.0);
  }
}

double acceleration(const Sled& sled, const BlockSystem& s, double g, double u, double d, double v) {
  double drive = 0.0, resist = 0.0;
  forces(sled, s, g, u, d, v, &drive, &resist);
  if (v > 0.0) return (drive - resist) / sled.mass;
  if (v < 0.0) return (drive + resist) / sled.mass;
  if (std::abs(drive) <= resist) return 0.0;  // held by static friction
  return (drive - std::copysign(resist, drive)) / sled.mass;
}

}  // namespace

SledRecord run_sled(const Scene& scene, BlockSystem& s, RunRecorder& recorder, SimulationSummary& summary) {
  SledRecord out;
  for (const Interface& f : scene.interfaces)
    if (f.law == FrictionLaw::ThermalPressurization) {
      summary.status = RunStatus::InvalidScene;
      summary.message = "interfaces." + f.name + ".law: thermal_pressurization needs the stress history of the DDA "
                        "solvers; the sled does not model it (use time.integrator: implicit or substep)";
      return out;
    }
  const Sled sled = build(scene, s);
  if (sled.slices.empty()) {
    summary.status = RunStatus::InvalidScene;
    summary.message = "the sled found no free block resting on a fixed one through an interface: it needs a slide "
                      "(free blocks) above a ground (fixed blocks)";
    return out;
  }
  if (sled.unsupported > 0)
    summary.warnings.push_back(std::to_string(sled.unsupported) + " of the sled's slices have no fixed block under "
                               "them or no interface to it (a contacts rule missing?): their mass is left out");
  if (scene.water.present() || scene.earthquake.present())
    summary.warnings.push_back("the sled ignores water: and earthquake: (the DDA solvers model them)");
  const double g = scene.gravity.norm();
  out.path_length = sled.path.length();
  out.slices = static_cast<int>(sled.slices.size());
  double sum_sin = 0.0, sum_cos = 0.0;
  for (const Slice& slice : sled.slices) {
    const Vec2 t = sled.path.tangent(slice.start);
    sum_sin += slice.mass * -t.y();
    sum_cos += slice.mass * t.x();
  }
  out.static_friction_angle = std::atan2(sum_sin, sum_cos) * 180.0 / kPi;

  recorder.start(s);
  double time = 0.0, u = 0.0, d = 0.0, v = 0.0;
  out.series.push_back({0.0, 0.0, 0.0});
  const double step = scene.max_step;
  const auto f = [&](double uu, double dd, double vv) { return acceleration(sled, s, g, uu, dd, vv); };
  double smallest = step, largest = 0.0;
  long steps = 0;
  while (!recorder.finished(time) && !recorder.interrupted(time, s)) {
    double landing = -1.0;
    const double dt = recorder.fit_step(time, step, &landing);
    // RK4; the friction's sign follows the speed at each stage, and a sled whose speed would
    // change sign within the step has stopped in it.
    // (u, d, v): d' = |v|, the slip; within one step the speed keeps its sign (a sign change
    // is a stop, below), so |u - start| and d - start agree.
    const double k1u = v, k1v = f(u, d, v);
    const double k2u = v + 0.5 * dt * k1v, k2v = f(u + 0.5 * dt * k1u, d + 0.5 * dt * std::abs(k1u), v + 0.5 * dt * k1v);
    const double k3u = v + 0.5 * dt * k2v, k3v = f(u + 0.5 * dt * k2u, d + 0.5 * dt * std::abs(k2u), v + 0.5 * dt * k2v);
    const double k4u = v + dt * k3v, k4v = f(u + dt * k3u, d + dt * std::abs(k3u), v + dt * k3v);
    double nu = u + dt / 6.0 * (k1u + 2 * k2u + 2 * k3u + k4u);
    double nv = v + dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (v != 0.0 && nv * v <= 0.0) {
      nu = u + 0.5 * v * dt * v / (v - nv);  // to rest where the speed crosses zero
      nv = 0.0;
    }
    const double nd = d + std::abs(nu - u);
    // Each free block moves with the slice under its centroid.
    std::vector<Vec2> moved(sled.slices.size());
    for (size_t k = 0; k < sled.slices.size(); ++k)
      moved[k] = sled.path.at(sled.slices[k].start + nu) - sled.path.at(sled.slices[k].start + u);
    for (int b = 0; b < static_cast<int>(s.blocks.size()); ++b) {
      const int k = sled.block_slice[b];
      if (k < 0) continue;
      Vec6 d = Vec6::Zero();
      d.head<2>() = moved[k];
      displace_block(s, b, d, true);
      const Vec2 velocity = nv * sled.path.tangent(sled.slices[k].start + nu);
      s.blocks[b].velocity = Vec6::Zero();
      s.blocks[b].velocity.head<2>() = velocity;
    }
    u = nu;
    d = nd;
    v = nv;
    smallest = std::min(smallest, dt);
    largest = std::max(largest, dt);
    time = landing >= 0.0 ? landing : time + dt;
    ++steps;
    out.series.push_back({time, u, v});
    recorder.record(time, s);
  }
  summary.run.steps = steps;
  summary.run.simulated_time = time;
  summary.run.smallest_step = smallest;
  summary.run.largest_step = largest;
  return out;
}

}  // namespace ddafit
