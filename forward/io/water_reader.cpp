#include "forward/io/water_reader.hpp"

#include "forward/io/region_reader.hpp"

namespace ddafit::io {

void read_water(const YamlChecks& c, const YAML::Node& water, const std::string& base_dir, Scene& s) {
  if (!water.IsMap()) c.fail("water", "expected a map: {level: Z} or {table: FILE.csv}, and density");
  c.check_keys(water, "water", {"level", "table", "density"});
  Water& w = s.water;
  if (const YAML::Node n = water["level"]) w.level = c.number(n, "water.level");
  if (const YAML::Node t = water["table"]) {
    if (t.IsScalar()) {
      w.table = read_polyline_csv(c, resolve_input_path(base_dir, c.text(t, "water.table")), "water.table");
    } else {
      // As the writer gives it: [[x, z], ...], x increasing.
      c.list(t, "water.table");
      for (size_t k = 0; k < t.size(); ++k) {
        const Vec2 p = c.vec2(t[k], indexed("water.table", k));
        if (!w.table.empty() && !(p.x() > w.table.back().x()))
          c.fail(indexed("water.table", k), "x must increase along the water table");
        w.table.push_back(p);
      }
      if (w.table.size() < 2) c.fail("water.table", "give at least two points [x, z]");
    }
  }
  c.opt_number(water, "water", "density", w.density);
  if (!w.present()) c.fail("water", "give level: Z (m), table: FILE.csv (columns x_m,z_m), or both");
}

}  // namespace ddafit::io
