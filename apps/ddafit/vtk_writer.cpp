#include "apps/ddafit/vtk_writer.hpp"

#include <fmt/os.h>

namespace ddafit::app {
namespace {

struct Cells {
  std::vector<Vec2> points;
  std::vector<std::vector<int>> polygons;
  std::vector<int> block, fixed, group;
  std::vector<double> value;  // area or speed
};

void write(const std::string& path, const Cells& c, const std::string& title, const char* value_name) {
  auto out = fmt::output_file(path);
  out.print("# vtk DataFile Version 3.0\n{}\nASCII\nDATASET POLYDATA\n", title);
  out.print("POINTS {} double\n", c.points.size());
  for (const Vec2& p : c.points) out.print("{:.10g} {:.10g} 0\n", p.x(), p.y());
  size_t size = 0;
  for (const auto& poly : c.polygons) size += poly.size() + 1;
  out.print("POLYGONS {} {}\n", c.polygons.size(), size);
  for (const auto& poly : c.polygons) {
    out.print("{}", poly.size());
    for (int v : poly) out.print(" {}", v);
    out.print("\n");
  }
  out.print("CELL_DATA {}\n", c.polygons.size());
  out.print("SCALARS block int 1\nLOOKUP_TABLE default\n");
  for (int b : c.block) out.print("{}\n", b);
  out.print("SCALARS fixed int 1\nLOOKUP_TABLE default\n");
  for (int f : c.fixed) out.print("{}\n", f);
  out.print("SCALARS group int 1\nLOOKUP_TABLE default\n");
  for (int g : c.group) out.print("{}\n", g);
  out.print("SCALARS {} double 1\nLOOKUP_TABLE default\n", value_name);
  for (double v : c.value) out.print("{:.8g}\n", v);
}

}  // namespace

void write_scene_vtk(const std::string& path, const Scene& scene) {
  Cells c;
  std::vector<std::string> groups;
  for (size_t b = 0; b < scene.blocks.size(); ++b) {
    const BlockInput& in = scene.blocks[b];
    std::vector<int> poly;
    for (const Vec2& p : in.polygon) {
      poly.push_back(static_cast<int>(c.points.size()));
      c.points.push_back(p);
    }
    c.polygons.push_back(poly);
    c.block.push_back(static_cast<int>(b));
    c.fixed.push_back(in.fixed ? 1 : 0);
    const std::string& g = in.group.empty() ? in.name : in.group;
    auto it = std::find(groups.begin(), groups.end(), g);
    if (it == groups.end()) it = groups.insert(groups.end(), g);
    c.group.push_back(static_cast<int>(it - groups.begin()));
    double area = 0.0;
    for (size_t k = 0; k < in.polygon.size(); ++k) {
      const Vec2& a = in.polygon[k];
      const Vec2& d = in.polygon[(k + 1) % in.polygon.size()];
      area += 0.5 * (a.x() * d.y() - d.x() * a.y());
    }
    c.value.push_back(std::abs(area));
  }
  write(path, c, "ddafit blocks", "area");
}

void write_state_vtk(const std::string& path, const BlockSystem& s, double time) {
  Cells c;
  c.points = s.vertices;
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    const Block& block = s.blocks[b];
    std::vector<int> poly;
    for (int v = block.first_vertex; v < block.first_vertex + block.vertex_count; ++v) poly.push_back(v);
    c.polygons.push_back(poly);
    c.block.push_back(static_cast<int>(b));
    c.fixed.push_back(block.fixed ? 1 : 0);
    c.group.push_back(block.group);
    c.value.push_back(Vec2(block.velocity[0], block.velocity[1]).norm());
  }
  write(path, c, fmt::format("ddafit state t={:.6g} s", time), "speed");
}

}  // namespace ddafit::app
