// Checks a Scene (and its SimulationOptions) before a run, so that a bad input is
// reported once, in the user's terms (YAML keys), instead of surfacing later as a
// singular matrix or a block that flies apart.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "forward/geometry.hpp"
#include "forward/options.hpp"
#include "forward/scene.hpp"
#include "forward/value_checks.hpp"

namespace ddafit {

namespace {

std::string num(double v) { return shortest_text(v); }

// Three significant digits, for counts the code derived (steps, rows), not values the
// user typed.
std::string approx(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

bool finite(double v) { return std::isfinite(v); }
bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

struct Box {
  Vec2 lo = Vec2::Zero();
  Vec2 hi = Vec2::Zero();
  double diagonal() const { return (hi - lo).norm(); }
  bool intersects(const Box& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y();
  }
};

Box bounding_box(const std::vector<Vec2>& polygon) {
  Box b{polygon.front(), polygon.front()};
  for (const Vec2& p : polygon) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

std::string block_key(size_t k, const char* field) {
  return "blocks[" + std::to_string(k) + "]." + field;
}

std::string named_key(const char* section, const std::string& name, size_t k, const char* field) {
  // Materials and interfaces are YAML maps keyed by name; scenes built in code may
  // leave the name empty, so fall back to the index.
  const std::string entry = name.empty() ? std::string(section) + "[" + std::to_string(k) + "]"
                                         : std::string(section) + "." + name;
  return entry + "." + field;
}

// What is wrong with a block outline, or "" when it is usable for the overlap and
// measure-point tests that follow.
std::string polygon_problem(const std::vector<Vec2>& poly) {
  const size_t n = poly.size();
  if (n < 3) return "has " + std::to_string(n) + " vertices; a polygon needs at least 3";
  for (size_t i = 0; i < n; ++i)
    if (!finite(poly[i]))
      return "has a non-finite coordinate at vertex " + std::to_string(i) + "; give numbers";
  const double diag = bounding_box(poly).diagonal();
  // Coincident within round-off of the block size, which would make a zero-length edge.
  const double same = 1e-12 * diag;
  if ((poly[n - 1] - poly[0]).norm() <= same)
    return "ends with its first vertex again; do not repeat the first vertex, the polygon "
           "closes itself";
  for (size_t i = 0; i + 1 < n; ++i)
    if ((poly[i + 1] - poly[i]).norm() <= same)
      return "has vertices " + std::to_string(i) + " and " + std::to_string(i + 1) +
             " at the same point; remove the repeated vertex";
  // Crossing edges before area: a symmetric bow-tie also has zero area, and "zero area"
  // would send the user looking for the wrong mistake.
  const auto [e1, e2] = first_self_intersection(poly);
  if (e1 >= 0) {
    auto edge = [n](int e) {
      return "edge " + std::to_string(e) + " (vertex " + std::to_string(e) + " to " +
             std::to_string((e + 1) % static_cast<int>(n)) + ")";
    };
    return "is not simple: " + edge(e1) + " crosses " + edge(e2) +
           "; reorder the vertices along the outline";
  }
  if (std::abs(signed_area(poly)) <= 1e-12 * diag * diag)
    return "has zero area (degenerate, e.g. collinear vertices); give a proper outline";
  return {};
}

// Candidate pairs of intersecting bounding boxes from a uniform grid, so that scenes
// with 10^4 blocks do not need all n^2/2 pair tests. Each pair is reported once: in the
// cell that holds the lower-left corner of the intersection of the two boxes.
std::vector<std::pair<int, int>> box_pairs(const std::vector<Box>& boxes,
                                           const std::vector<int>& ids) {
  std::vector<std::pair<int, int>> pairs;
  if (ids.size() < 2) return pairs;
  Box all = boxes[ids[0]];
  std::vector<double> widths, heights;
  for (int id : ids) {
    all.lo = all.lo.cwiseMin(boxes[id].lo);
    all.hi = all.hi.cwiseMax(boxes[id].hi);
    widths.push_back(boxes[id].hi.x() - boxes[id].lo.x());
    heights.push_back(boxes[id].hi.y() - boxes[id].lo.y());
  }
  // Cell = median block width x median height: per axis, so that slender blocks do not
  // all share one cell; a large base block spans many cells, which is cheap. Cells are
  // enlarged if needed to keep about 4 per block. (Usable blocks have non-zero area.)
  auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const Vec2 span = all.hi - all.lo;
  Vec2 h(median(widths), median(heights));
  const double max_cells = 4.0 * static_cast<double>(ids.size()) + 16.0;
  const double cells = (span.x() / h.x() + 1.0) * (span.y() / h.y() + 1.0);
  if (cells > max_cells) h *= std::sqrt(cells / max_cells);
  const int nx = static_cast<int>(span.x() / h.x()) + 1;
  const int ny = static_cast<int>(span.y() / h.y()) + 1;
  auto cell_x = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x - all.lo.x()) / h.x())), 0, nx - 1);
  };
  auto cell_y = [&](double y) {
    return std::clamp(static_cast<int>(std::floor((y - all.lo.y()) / h.y())), 0, ny - 1);
  };

  std::vector<std::vector<int>> grid(static_cast<size_t>(nx) * ny);
  for (int id : ids) {
    const Box& b = boxes[id];
    for (int iy = cell_y(b.lo.y()); iy <= cell_y(b.hi.y()); ++iy)
      for (int ix = cell_x(b.lo.x()); ix <= cell_x(b.hi.x()); ++ix)
        grid[static_cast<size_t>(iy) * nx + ix].push_back(id);
  }
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      const auto& members = grid[static_cast<size_t>(iy) * nx + ix];
      for (size_t a = 0; a < members.size(); ++a) {
        for (size_t b = a + 1; b < members.size(); ++b) {
          const Box& p = boxes[members[a]];
          const Box& q = boxes[members[b]];
          if (!p.intersects(q)) continue;
          const double cx = std::max(p.lo.x(), q.lo.x());
          const double cy = std::max(p.lo.y(), q.lo.y());
          if (cell_x(cx) != ix || cell_y(cy) != iy) continue;
          pairs.emplace_back(std::min(members[a], members[b]), std::max(members[a], members[b]));
        }
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());  // report in input order
  return pairs;
}


constexpr double kMaxSteps = 1e8;         // ~30 h of wall even at 1 ms a step
constexpr double kMaxHistoryRows = 1e7;   // ~700 MB of history.csv

// Appends "KEY: is VALUE; RULE" unless the value passed its check.
void expect(bool ok, const std::string& key, double value, const char* rule,
            std::vector<SceneError>& errors) {
  if (!ok) errors.push_back({key, "is " + num(value) + "; " + rule});
}

// A record as the reader makes it: at least two samples, finite, at increasing, even times
// (docs/earthquakes.md).
void check_earthquake(const GroundMotion& g, std::vector<SceneError>& errors) {
  const std::string key = "earthquake.record";
  expect(non_negative(g.scale), "earthquake.scale", g.scale, "must be >= 0", errors);
  if (g.time.size() != g.acceleration.size() || g.time.size() < 2) {
    errors.push_back({key, "needs at least two samples, each a time and an acceleration"});
    return;
  }
  const double first = g.time[1] - g.time[0];
  for (size_t k = 0; k < g.time.size(); ++k) {
    const std::string at = key + "[" + std::to_string(k) + "]";
    if (!std::isfinite(g.time[k]) || !finite(g.acceleration[k])) {
      errors.push_back({at, "is not finite"});
      return;
    }
    if (g.time[k] < 0.0) {
      errors.push_back({at, "its time is before the run starts (t = 0)"});
      return;
    }
    if (k > 0 && !(g.time[k] > g.time[k - 1])) {
      errors.push_back({at, "its time does not increase"});
      return;
    }
    if (k > 0 && std::abs(g.time[k] - g.time[k - 1] - first) > kEvenRecordStep * first) {
      errors.push_back({at, "uneven time step: resample the record at an even step"});
      return;
    }
  }
}

void check_settings(const Scene& scene, std::vector<SceneError>& errors) {
  if (!finite(scene.gravity))
    errors.push_back({"gravity", "is not finite; give two numbers, e.g. [0, -9.81]"});
  expect(positive(scene.duration), "time.duration", scene.duration, "must be > 0 seconds", errors);
  expect(scene.max_step > 0 && scene.max_step <= scene.duration, "time.step", scene.max_step,
         "must be > 0 and not longer than time.duration", errors);
  expect(non_negative(scene.output_interval), "output.interval", scene.output_interval,
         "must be >= 0 (0 = every step)", errors);
  expect(positive(scene.rest_speed), "rest_speed", scene.rest_speed, "must be > 0 m/s", errors);
  if (scene.water.present()) {
    expect(positive(scene.water.density), "water.density", scene.water.density, "must be > 0 kg/m^3", errors);
    // z is the scene's y: the hydrostatic pressure needs gravity along -y.
    if (!(scene.gravity.x() == 0.0 && scene.gravity.y() < 0.0))
      errors.push_back({"water", "needs gravity along -y (the water surface's z is the scene's y)"});
  }
  if (scene.earthquake.present()) check_earthquake(scene.earthquake, errors);
  // A run must end and its output must fit: the steps it takes at the largest step and the
  // history rows it writes are bounded (an output interval of 1e-14 s once stalled at 0 %
  // forever, and a step of 1e-300 s ran without end).
  if (positive(scene.duration) && scene.max_step > 0) {
    const double steps = scene.duration / scene.max_step;
    if (steps > kMaxSteps)
      errors.push_back({"time.step", "is " + num(scene.max_step) + " s: time.duration / time.step = " + approx(steps) +
                                         " steps, more than the " + approx(kMaxSteps) +
                                         " a run may take; raise time.step or shorten time.duration"});
    const double interval = scene.output_interval > 0 ? scene.output_interval : scene.max_step;
    const double points = static_cast<double>(std::max<size_t>(1, scene.measure.size()));
    const double rows = (scene.duration / interval + 1.0) * points;
    if (steps <= kMaxSteps && rows > kMaxHistoryRows)
      errors.push_back({scene.output_interval > 0 ? "output.interval" : "time.step",
                        "would write " + approx(rows) + " history rows (" + approx(points) + " points over " +
                            num(scene.duration) + " s), more than the " + approx(kMaxHistoryRows) +
                            " a run may write; raise output.interval"});
  }
  const std::string bad = validate_options(scene.options);
  if (!bad.empty()) {
    const size_t colon = bad.find(": ");
    errors.push_back({bad.substr(0, colon), bad.substr(colon + 2)});
  }
}

void check_materials_and_interfaces(const Scene& scene, std::vector<SceneError>& errors) {
  std::set<std::string> seen;
  for (size_t k = 0; k < scene.materials.size(); ++k) {
    const Material& m = scene.materials[k];
    auto key = [&](const char* field) { return named_key("materials", m.name, k, field); };
    if (!seen.insert(m.name).second)
      errors.push_back({key("name"), "material '" + m.name + "' is defined twice; rename one"});
    expect(positive(m.density), key("density"), m.density, "must be > 0 kg/m^3", errors);
    expect(positive(m.young_modulus), key("young_modulus"), m.young_modulus, "must be > 0 Pa",
           errors);
    expect(m.poisson_ratio >= 0 && m.poisson_ratio < 0.5, key("poisson_ratio"), m.poisson_ratio,
           "must be in [0, 0.5)", errors);
  }
  seen.clear();
  for (size_t k = 0; k < scene.interfaces.size(); ++k) {
    const Interface& f = scene.interfaces[k];
    auto key = [&](const char* field) { return named_key("interfaces", f.name, k, field); };
    if (!seen.insert(f.name).second)
      errors.push_back({key("name"), "interface '" + f.name + "' is defined twice; rename one"});
    expect(f.friction_angle >= 0 && f.friction_angle < 90, key("friction_angle"),
           f.friction_angle, "must be in [0, 90) degrees", errors);
    expect(non_negative(f.cohesion), key("cohesion"), f.cohesion, "must be >= 0 Pa", errors);
    expect(non_negative(f.tensile_strength), key("tensile_strength"), f.tensile_strength,
           "must be >= 0 Pa", errors);
    expect(f.roughness_angle >= 0 && f.roughness_angle <= f.friction_angle,
           key("roughness_angle"), f.roughness_angle,
           "must be in [0, friction_angle] so the residual angle is >= 0", errors);
    expect(positive(f.critical_distance_ratio), key("critical_distance_ratio"),
           f.critical_distance_ratio, "must be > 0", errors);
    expect(positive(f.weakening_velocity), key("weakening_velocity"), f.weakening_velocity, "must be > 0 m/s",
           errors);
    if (f.law == FrictionLaw::ThermalPressurization) {
      expect(positive(f.band_thickness), key("band_thickness"), f.band_thickness, "must be > 0 m", errors);
      expect(positive(f.heat_capacity), key("heat_capacity"), f.heat_capacity, "must be > 0 J/m^3/K", errors);
      expect(non_negative(f.pressurization_factor), key("pressurization_factor"), f.pressurization_factor,
             "must be >= 0 Pa/K", errors);
      expect(non_negative(f.thermal_diffusivity), key("thermal_diffusivity"), f.thermal_diffusivity,
             "must be >= 0 m^2/s", errors);
      expect(non_negative(f.hydraulic_diffusivity), key("hydraulic_diffusivity"), f.hydraulic_diffusivity,
             "must be >= 0 m^2/s", errors);
      if (f.roughness_angle != 0.0)
        errors.push_back({key(f.degradation_percent ? "degradation_percent" : "roughness_angle"),
                          "law thermal_pressurization reads no roughness: its strength falls with the shear band's "
                          "pore pressure; give 0 or leave it out"});
    }
  }
}

// Blocks and measure points are identified by name in the output.
void check_name(const std::string& name, const std::string& list, size_t k,
                std::map<std::string, size_t>& first_use, std::vector<SceneError>& errors) {
  const std::string key = list + "[" + std::to_string(k) + "].name";
  const auto [it, fresh] = first_use.emplace(name, k);
  if (name.empty())
    errors.push_back({key, "is empty; give a unique name"});
  else if (!fresh)
    errors.push_back({key, "'" + name + "' is also the name of " + list + "[" +
                               std::to_string(it->second) + "]; names must be unique"});
}

// Returns the indices of blocks whose polygons passed the checks.
std::vector<int> check_blocks(const Scene& scene, std::vector<SceneError>& errors) {
  std::vector<int> usable;
  std::map<std::string, size_t> first_use;
  bool any_free = false;
  const int materials = static_cast<int>(scene.materials.size());
  for (size_t k = 0; k < scene.blocks.size(); ++k) {
    const BlockInput& b = scene.blocks[k];
    const std::string who = "block '" + b.name + "'";
    check_name(b.name, "blocks", k, first_use, errors);
    if (b.material < 0 || b.material >= materials)
      errors.push_back({block_key(k, "material"),
                        who + " refers to material index " + std::to_string(b.material) +
                            ", which does not exist; use a defined material"});
    if (const std::string problem = polygon_problem(b.polygon); problem.empty())
      usable.push_back(static_cast<int>(k));
    else
      errors.push_back({block_key(k, "polygon"), who + " " + problem});
    if (!finite(b.velocity))
      errors.push_back({block_key(k, "velocity"), who + ": velocity is not finite; give [vx, vy]"});
    if (!finite(b.angular_velocity))
      errors.push_back({block_key(k, "angular_velocity"),
                        who + ": angular_velocity is not finite; give rad/s"});
    any_free = any_free || !b.fixed;
  }
  if (!any_free)
    errors.push_back({"blocks", "every block is fixed, so nothing can move; "
                                "set fixed: false (the default) on at least one block"});
  return usable;
}

void check_overlaps(const Scene& scene, const std::vector<Box>& boxes,
                    const std::vector<int>& usable, std::vector<SceneError>& errors) {
  // Each block is named in at most one overlap message: a scene where everything
  // overlaps would otherwise produce n^2 messages.
  std::vector<bool> reported(scene.blocks.size(), false);
  for (const auto& [i, j] : box_pairs(boxes, usable)) {
    if (reported[i] || reported[j]) continue;
    // Tolerance relative to the smaller block: touching along a shared edge is the
    // normal state of a DDA mesh and must pass despite round-off in the coordinates.
    const double tol = 1e-6 * std::min(boxes[i].diagonal(), boxes[j].diagonal());
    if (!polygons_overlap(scene.blocks[i].polygon, scene.blocks[j].polygon, tol)) continue;
    reported[i] = reported[j] = true;
    errors.push_back({block_key(j, "polygon"),
                      "block '" + scene.blocks[j].name + "' overlaps block '" +
                          scene.blocks[i].name + "' (blocks[" + std::to_string(i) +
                          "]); blocks may touch but not overlap"});
  }
}

void check_contacts(const Scene& scene, std::vector<SceneError>& errors) {
  const int count = static_cast<int>(scene.interfaces.size());
  std::map<std::pair<std::string, std::string>, size_t> pairs;
  for (size_t k = 0; k < scene.contact_rules.size(); ++k) {
    const ContactRule& r = scene.contact_rules[k];
    const std::string key = "contacts[" + std::to_string(k) + "]";
    if (r.interface < 0 || r.interface >= count)
      errors.push_back({key, "refers to interface index " + std::to_string(r.interface) +
                                 ", which does not exist; use a defined interface"});
    // The same group pair with two rules would make the interface ambiguous.
    const auto pair = std::minmax(r.group_a, r.group_b);
    const auto [it, fresh] = pairs.emplace(std::make_pair(pair.first, pair.second), k);
    if (!fresh)
      errors.push_back({key, "groups '" + r.group_a + "' and '" + r.group_b +
                                 "' already have a rule in contacts[" +
                                 std::to_string(it->second) + "]; keep one"});
  }
  if (scene.default_interface < -1 || scene.default_interface >= count)
    errors.push_back({"default_interface", "refers to interface index " +
                                               std::to_string(scene.default_interface) +
                                               ", which does not exist"});
}

void check_measure(const Scene& scene, const std::vector<Box>& boxes,
                   const std::vector<int>& usable, std::vector<SceneError>& errors) {
  std::map<std::string, size_t> first_use;
  for (size_t k = 0; k < scene.measure.size(); ++k) {
    const MeasurePoint& m = scene.measure[k];
    const std::string base = "measure[" + std::to_string(k) + "]";
    check_name(m.name, "measure", k, first_use, errors);
    if (!finite(m.at)) {
      errors.push_back({base + ".at", "is not finite; give [x, y]"});
      continue;
    }
    // Measure points are few, so a scan with a bounding-box pre-filter is enough.
    bool inside = false;
    for (int id : usable) {
      const double tol = 1e-9 * boxes[id].diagonal();
      const Box& b = boxes[id];
      if ((m.at - b.lo).minCoeff() < -tol || (b.hi - m.at).minCoeff() < -tol) continue;
      const auto& poly = scene.blocks[id].polygon;
      if (point_in_polygon(m.at, poly) || distance_to_boundary(m.at, poly) <= tol) {
        inside = true;
        break;
      }
    }
    if (!inside)
      errors.push_back({base + ".at", "point '" + m.name + "' at (" + num(m.at.x()) + ", " +
                                          num(m.at.y()) + ") is outside every block; "
                                          "place it inside the block to follow"});
  }
}

}  // namespace

const char* to_string(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::Bilinear: return "bilinear";
    case FrictionLaw::Exponential: return "exponential";
    case FrictionLaw::VelocityWeakening: return "velocity_weakening";
    case FrictionLaw::ThermalPressurization: return "thermal_pressurization";
  }
  return "?";
}

std::vector<SceneError> validate_scene(const Scene& scene) {
  // All problems are collected, in roughly the order they appear in a scene file;
  // callers that stop at one report the first.
  std::vector<SceneError> errors;
  check_settings(scene, errors);
  check_materials_and_interfaces(scene, errors);
  const std::vector<int> usable = check_blocks(scene, errors);
  std::vector<Box> boxes(scene.blocks.size());
  for (int id : usable) boxes[id] = bounding_box(scene.blocks[id].polygon);
  check_overlaps(scene, boxes, usable, errors);
  check_contacts(scene, errors);
  check_measure(scene, boxes, usable, errors);
  return errors;
}

}  // namespace ddafit
