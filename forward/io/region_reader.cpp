#include "forward/io/region_reader.hpp"
#include "forward/io/text_input.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "forward/geometry.hpp"
#include "forward/mesh/region.hpp"

namespace ddafit::io {
namespace {

// y of a polyline (increasing x) at x, by linear interpolation.
double height_at(const std::vector<Vec2>& line, double x) {
  for (size_t k = 0; k + 1 < line.size(); ++k)
    if (x <= line[k + 1].x()) {
      const double t = (x - line[k].x()) / (line[k + 1].x() - line[k].x());
      return line[k].y() + t * (line[k + 1].y() - line[k].y());
    }
  return line.back().y();
}

// The part of a polyline between x0 and x1, with interpolated end points.
std::vector<Vec2> slice(const std::vector<Vec2>& line, double x0, double x1) {
  std::vector<Vec2> out{Vec2(x0, height_at(line, x0))};
  for (const Vec2& p : line)
    if (p.x() > x0 && p.x() < x1) out.push_back(p);
  out.emplace_back(x1, height_at(line, x1));
  return out;
}

// Drops consecutive repeats (where two boundary polylines meet at an end).
std::vector<Vec2> without_repeats(std::vector<Vec2> ring) {
  std::vector<Vec2> out;
  for (const Vec2& p : ring)
    if (out.empty() || (p - out.back()).norm() > 1e-9) out.push_back(p);
  while (out.size() > 1 && (out.front() - out.back()).norm() <= 1e-9) out.pop_back();
  return out;
}

}  // namespace

std::string resolve_input_path(const std::string& base_dir, const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() || base_dir.empty() ? file : (std::filesystem::path(base_dir) / p).string();
}

std::vector<Vec2> read_polyline_csv(const YamlChecks& checks, const std::string& path, const std::string& key) {
  std::string problem;
  std::istringstream in(read_input_file(path, problem));
  if (!problem.empty()) checks.fail(key, problem);
  std::vector<Vec2> line;
  std::string row;
  bool header_allowed = true;  // one line of column names before the first point
  for (int number = 1; std::getline(in, row); ++number) {
    if (row.empty() || row[0] == '#') continue;
    std::replace(row.begin(), row.end(), ',', ' ');
    std::istringstream fields(row);
    double x, y;
    const bool parsed = static_cast<bool>(fields >> x >> y);
    const bool header = !parsed && header_allowed;
    header_allowed = false;
    if (header) continue;
    if (!parsed) {
      checks.fail(key, "'" + path + "' line " + std::to_string(number) + ": expected two numbers x,y");
    }
    if (!line.empty() && !(x > line.back().x()))
      checks.fail(key, "'" + path + "' line " + std::to_string(number) + ": x must increase along the polyline");
    line.emplace_back(x, y);
  }
  if (line.size() < 2) checks.fail(key, "'" + path + "' has fewer than two points");
  return line;
}

void read_regions(const YamlChecks& c, const YAML::Node& root, const std::string& base_dir, Scene& s) {
  const YAML::Node mesh = root["mesh"], regions = root["regions"];
  if (mesh) {
    c.check_keys(mesh, "mesh", {"block_size", "min_area_ratio", "min_angle", "min_edge_ratio", "max_arrangement_edges"});
    if (const YAML::Node n = mesh["block_size"]) s.mesh.block_size = c.length(n, "mesh.block_size");
    c.opt_number(mesh, "mesh", "min_area_ratio", s.mesh.min_area_ratio);
    c.opt_number(mesh, "mesh", "min_angle", s.mesh.min_angle);
    c.opt_number(mesh, "mesh", "min_edge_ratio", s.mesh.min_edge_ratio);
    c.opt_number(mesh, "mesh", "max_arrangement_edges", s.mesh.max_arrangement_edges);
    for (const SceneError& e : validate_mesh_settings(s.mesh)) c.fail(e.key, e.problem);
  }
  if (!regions) return;
  c.list(regions, "regions");
  for (size_t k = 0; k < regions.size(); ++k) {
    const std::string path = indexed("regions", k);
    const YAML::Node r = regions[k];
    c.check_keys(r, path, {"name", "group", "material", "fixed", "block_size", "polygon", "between", "below",
                           "joint_sets"});
    RegionInput region;
    region.name = c.text(c.required(r, path, "name", "give the region a name"), path + ".name");
    if (const YAML::Node g = r["group"]) region.group = c.text(g, path + ".group");
    region.material = c.find(s.materials, c.text(c.required(r, path, "material", "name a material"), path + ".material"),
                             path + ".material", "material");
    if (const YAML::Node f = r["fixed"]) region.fixed = c.scalar<bool>(f, path + ".fixed", "true or false");
    if (const YAML::Node n = r["block_size"]) region.block_size = c.length(n, path + ".block_size");
    const int shapes = (r["polygon"] ? 1 : 0) + (r["between"] ? 1 : 0) + (r["below"] ? 1 : 0);
    if (shapes != 1) c.fail(path, "give exactly one of polygon, between or below");
    if (const YAML::Node p = r["polygon"]) {
      c.list(p, path + ".polygon");
      for (size_t q = 0; q < p.size(); ++q) region.polygon.push_back(c.vec2(p[q], indexed(path + ".polygon", q)));
    } else if (const YAML::Node b = r["between"]) {
      const std::string bp = path + ".between";
      c.check_keys(b, bp, {"upper", "lower", "x_min", "x_max"});
      const auto upper = read_polyline_csv(c, resolve_input_path(base_dir, c.text(c.required(b, bp, "upper", "a CSV file"), bp + ".upper")), bp + ".upper");
      const auto lower = read_polyline_csv(c, resolve_input_path(base_dir, c.text(c.required(b, bp, "lower", "a CSV file"), bp + ".lower")), bp + ".lower");
      double x0 = std::max(upper.front().x(), lower.front().x()), x1 = std::min(upper.back().x(), lower.back().x());
      c.opt_number(b, bp, "x_min", x0);
      c.opt_number(b, bp, "x_max", x1);
      if (!(x0 < x1)) c.fail(bp, "x_min must be below x_max, inside both polylines' x ranges");
      std::vector<Vec2> ring = slice(upper, x0, x1);
      std::reverse(ring.begin(), ring.end());
      for (const Vec2& p : slice(lower, x0, x1)) ring.push_back(p);
      region.polygon = without_repeats(ring);
    } else {
      const YAML::Node below = r["below"];
      const std::string bp = path + ".below";
      c.check_keys(below, bp, {"surface", "base"});
      const auto surface = read_polyline_csv(
          c, resolve_input_path(base_dir, c.text(c.required(below, bp, "surface", "a CSV file"), bp + ".surface")), bp + ".surface");
      const double base = c.req_number(below, bp, "base", "give the elevation of the region's bottom");
      for (const Vec2& p : surface)
        if (!(p.y() > base)) c.fail(bp + ".base", "must lie below every point of the surface");
      region.polygon = surface;
      region.polygon.emplace_back(surface.back().x(), base);
      region.polygon.emplace_back(surface.front().x(), base);
    }
    if (region.polygon.size() < 3 || first_self_intersection(region.polygon).first >= 0 ||
        std::abs(signed_area(region.polygon)) <= 0.0)
      c.fail(path, "the region's outline is not a simple polygon with positive area");
    if (const YAML::Node sets = r["joint_sets"]) {
      c.list(sets, path + ".joint_sets");
      for (size_t q = 0; q < sets.size(); ++q) {
        const std::string jp = indexed(path + ".joint_sets", q);
        c.check_keys(sets[q], jp, {"dip", "parallel_to", "spacing", "spacing_ratio", "offset"});
        JointSet set;
        c.opt_number(sets[q], jp, "dip", set.dip);
        if (const YAML::Node n = sets[q]["spacing"]) set.spacing = c.length(n, jp + ".spacing");
        c.opt_number(sets[q], jp, "spacing_ratio", set.spacing_ratio);
        c.opt_number(sets[q], jp, "offset", set.offset);
        if (const YAML::Node pt = sets[q]["parallel_to"]) {
          if (sets[q]["dip"]) c.fail(jp, "give either dip (straight joints) or parallel_to (a polyline), not both");
          set.parallel_to = read_polyline_csv(c, resolve_input_path(base_dir, c.text(pt, jp + ".parallel_to")), jp + ".parallel_to");
        }
        if (!(set.dip >= 0.0 && set.dip <= 180.0)) c.fail(jp + ".dip", "must be in [0, 180] degrees");
        if (!(set.spacing_ratio > 0.0 && set.spacing_ratio <= 1e3)) c.fail(jp + ".spacing_ratio", "must be in (0, 1000]");
        if (!(std::abs(set.offset) <= YamlChecks::kMaxLength)) c.fail(jp + ".offset", "must be within +-1e6 m");
        region.joint_sets.push_back(set);
      }
    }
    s.regions.push_back(region);
  }
}

}  // namespace ddafit::io
