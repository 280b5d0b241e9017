#include "forward/io/ddaml_import.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "forward/geometry.hpp"
#include "forward/kinematics.hpp"
#include "forward/io/scene_reader.hpp"
#include "forward/io/text_input.hpp"
#include "forward/io/xml_lite.hpp"
#include "forward/mesh/joint_lines.hpp"

namespace ddafit::io {
namespace {

// One file's elements with the file's name for messages.
struct Source {
  std::string label;
  XmlElement root;

  [[noreturn]] void refuse(const XmlElement& e, const std::string& why) const {
    throw SceneReadError(label + ": line " + std::to_string(e.line) + ": <" + e.name + ">: " + why);
  }
  // The numbers of an element's text; exactly `count` of them (or at least, if `at_least`).
  std::vector<double> numbers(const XmlElement& e, size_t count, bool at_least = false) const {
    std::vector<double> v;
    std::stringstream in(e.text);
    for (std::string token; in >> token;) {
      if (token == ";") continue;
      if (!token.empty() && token.back() == ';') token.pop_back();
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(x)) refuse(e, "'" + token + "' is not a number");
      v.push_back(x);
    }
    if (v.size() < count || (!at_least && v.size() > count))
      refuse(e, "needs " + std::to_string(count) + " numbers, has " + std::to_string(v.size()));
    return v;
  }
  double attribute_number(const XmlElement& e, const std::string& key) const {
    const std::string* value = e.attribute(key);
    if (!value) refuse(e, "attribute '" + key + "' is missing");
    char* end = nullptr;
    const double x = std::strtod(value->c_str(), &end);
    if (end == value->c_str() || !std::isfinite(x)) refuse(e, "attribute " + key + "=\"" + *value + "\" is not a number");
    return x;
  }
  // The section (Geometry or Analysis) among the root's children, or the root itself.
  const XmlElement& section(const std::string& name) const {
    if (root.name == name) return root;
    for (const XmlElement& c : root.children)
      if (c.name == name) return c;
    throw SceneReadError(label + ": no <" + name + "> element under <" + root.name + ">");
  }
};

Source load(const std::string& path) {
  std::string problem;
  const std::string text = read_input_file(path, problem);
  if (!problem.empty()) throw SceneReadError(problem);
  try {
    return {path, parse_xml(text, path)};
  } catch (const XmlError& e) {
    throw SceneReadError(e.what());
  }
}

struct Located {
  Vec2 a, b;  // a point has a == b
  int type = 0;
  int line = 0;
};

struct Geometry {
  std::vector<JointLine> joints;
  std::vector<Located> fixed, measured, holes, material_lines;
};

Geometry read_geometry(const Source& src) {
  Geometry g;
  const auto point = [&](const XmlElement& e) {
    const std::vector<double> v = src.numbers(e, 2);
    return Located{Vec2(v[0], v[1]), Vec2(v[0], v[1]), 0, e.line};
  };
  const auto segment = [&](const XmlElement& e, int type) {
    const std::vector<double> v = src.numbers(e, 4);
    return Located{Vec2(v[0], v[1]), Vec2(v[2], v[3]), type, e.line};
  };
  for (const XmlElement& list : src.section("Geometry").children) {
    const std::string& n = list.name;
    if (n == "Jointlist") {
      for (const XmlElement& j : list.children) {
        if (j.name != "Joint") continue;
        const Located s = segment(j, static_cast<int>(src.attribute_number(j, "type")));
        if (s.type < 1) src.refuse(j, "type=\"" + std::to_string(s.type) + "\": joint types start at 1");
        g.joints.push_back({s.a, s.b, s.type, s.line});
      }
    } else if (n == "Fixedpointlist") {
      for (const XmlElement& p : list.children) {
        if (p.name == "Point") g.fixed.push_back(point(p));
        else if (p.name == "Line") g.fixed.push_back(segment(p, 0));
      }
    } else if (n == "Measuredpointlist") {
      for (const XmlElement& p : list.children)
        if (p.name == "Point") g.measured.push_back(point(p));
    } else if (n == "Holepointlist") {
      for (const XmlElement& p : list.children)
        if (p.name == "Point") g.holes.push_back(point(p));
    } else if (n == "Matlinelist") {
      for (const XmlElement& l : list.children)
        if (l.name == "Line") g.material_lines.push_back(segment(l, static_cast<int>(src.attribute_number(l, "type"))));
    } else if (n == "Loadpointlist" || n == "Boltlist" || n == "Seismicpointlist" || n == "Boundlist") {
      const char* what = n == "Loadpointlist"   ? "point loads are not modelled by ddafit"
                         : n == "Boltlist"      ? "rock bolts are not modelled by ddafit"
                         : n == "Seismicpointlist" ? "seismic points: give the record as the scene's earthquake: instead"
                                                   : "boundary lines are not read by the DDA codes either (their reader drops them)";
      for (const XmlElement& p : list.children) src.refuse(p, what);
    }
  }
  if (g.joints.empty()) throw SceneReadError(src.label + ": <Jointlist> has no <Joint>: there are no blocks to cut");
  return g;
}

// Scale factors from the file's units to SI.
struct Scales {
  double density, stress;  // unit mass t/m^3 -> kg/m^3; kPa -> Pa
};

void read_analysis(const Source& src, const Scales& to_si, Scene& s, std::vector<Vec3>& initial_velocity,
                   std::vector<std::string>& notes) {
  double step = 0.0, steps = 0.0, save_interval = 1.0;
  const XmlElement* step_element = nullptr;
  for (const XmlElement& e : src.section("Analysis").children) {
    const std::string& n = e.name;
    const auto flag = [&] {
      const std::string* f = e.attribute("flag");
      if (!f) src.refuse(e, "attribute 'flag' is missing");
      return *f == "yes" || *f == "1" || *f == "true";
    };
    if (n == "Analysistype") {
      const std::string* type = e.attribute("type");
      if (!type || *type != "dynamic") src.refuse(e, "a static analysis: ddafit runs dynamic analyses only");
    } else if (n == "Numtimesteps") {
      steps = src.attribute_number(e, "timesteps");
    } else if (n == "Maxtimestep") {
      step = src.attribute_number(e, "maxtimestep");
      step_element = &e;
    } else if (n == "Saveinterval") {
      save_interval = std::max(1.0, src.attribute_number(e, "step"));
    } else if (n == "Gravaccel") {
      s.gravity = Vec2(0.0, -src.attribute_number(e, "value"));
    } else if (n == "Autopenalty") {
      if (e.attribute("pfactor")) s.options.penalty_factor = src.attribute_number(e, "pfactor");
    } else if (n == "Planestrain") {
      s.options.plane_strain = flag();
    } else if (n == "Opencloselimit" || n == "OCLimit") {
      s.options.max_open_close_iterations = static_cast<int>(src.attribute_number(e, "maxopenclose"));
    } else if (n == "Maxdisplacement") {
      s.options.max_displacement_ratio = src.attribute_number(e, "maxdisplacement");
    } else if (n == "Blockmaterial") {
      Material m;
      m.name = "material" + std::to_string(s.materials.size() + 1);
      Vec3 velocity = Vec3::Zero();
      for (const XmlElement& c : e.children) {
        if (c.name == "Unitmass") m.density = src.numbers(c, 1)[0] * to_si.density;
        else if (c.name == "Youngsmod") m.young_modulus = src.numbers(c, 1)[0] * to_si.stress;
        else if (c.name == "Poissonratio") m.poisson_ratio = src.numbers(c, 1)[0];
        else if (c.name == "Ivelocity") {
          const std::vector<double> v = src.numbers(c, 3);
          velocity = Vec3(v[0], v[1], v[2]);
        } else if (c.name == "Istress" || c.name == "Istrain") {
          for (const double x : src.numbers(c, 3))
            if (x != 0.0) src.refuse(c, c.name == "Istress" ? "initial stresses are not modelled by ddafit"
                                                           : "initial strains are not modelled by ddafit");
        }
      }
      s.materials.push_back(m);
      initial_velocity.push_back(velocity);
    } else if (n == "Jointproperties") {
      Interface f;
      f.name = "joint" + std::to_string(s.interfaces.size() + 1);
      for (const XmlElement& c : e.children) {
        if (c.name == "Friction") f.friction_angle = src.numbers(c, 1)[0];
        else if (c.name == "Cohesion") f.cohesion = src.numbers(c, 1)[0] * to_si.stress;
        else if (c.name == "Tensile") f.tensile_strength = src.numbers(c, 1)[0] * to_si.stress;
      }
      s.interfaces.push_back(f);
    } else if (n == "Timehistory") {
      src.refuse(e, "ground motion: give the record as the scene's earthquake: instead");
    }
  }
  if (!(step > 0.0)) throw SceneReadError(src.label + ": <Maxtimestep maxtimestep=...> is missing or not positive");
  if (!(steps >= 1.0)) throw SceneReadError(src.label + ": <Numtimesteps timesteps=...> is missing or below 1");
  (void)step_element;
  s.max_step = step;
  s.duration = steps * step;
  s.output_interval = save_interval * step;
  if (s.materials.empty()) throw SceneReadError(src.label + ": no <Blockmaterial>");
  if (s.interfaces.empty()) throw SceneReadError(src.label + ": no <Jointproperties>");
  notes.push_back("time: " + std::to_string(static_cast<long>(steps)) + " steps of " + std::to_string(step) +
                  " s; ddafit shortens a step where blocks move fast (docs/theory.md §8)");
}

// Placeholders when no analysis file is given, said in the notes.
void placeholder_analysis(Scene& s, std::vector<Vec3>& initial_velocity, int joint_types, std::vector<std::string>& notes) {
  s.materials.push_back({"material1", 2700.0, 5.0e9, 0.25, false});
  initial_velocity.push_back(Vec3::Zero());
  for (int t = 1; t <= joint_types; ++t) {
    Interface f;
    f.name = "joint" + std::to_string(t);
    f.friction_angle = 30.0;
    s.interfaces.push_back(f);
  }
  s.duration = 1.0;
  s.max_step = 1e-3;
  s.output_interval = 0.01;
  notes.push_back("no --analysis: placeholders written (material1: 2700 kg/m^3, E 5e9 Pa, nu 0.25; every joint "
                  "friction 30 deg; 1 s in 1 ms steps); edit them before running");
}

int block_containing(const std::vector<BlockInput>& blocks, const Vec2& p) {
  for (size_t b = 0; b < blocks.size(); ++b)
    if (point_in_polygon(p, blocks[b].polygon) || distance_to_boundary(p, blocks[b].polygon) < 1e-9) return static_cast<int>(b);
  return -1;
}

}  // namespace

DdamlImport import_ddaml(const std::string& geometry_path, const std::string& analysis_path, DdamlUnits units) {
  const Scales to_si = units == DdamlUnits::KiloNewton ? Scales{1000.0, 1000.0} : Scales{1.0, 1.0};
  const Source geo = load(geometry_path);
  const Geometry g = read_geometry(geo);
  DdamlImport out;
  Scene& s = out.scene;
  std::vector<Vec3> velocity_of;  // per material
  int joint_types = 0;
  for (const JointLine& j : g.joints) joint_types = std::max(joint_types, j.type);
  if (!analysis_path.empty()) {
    const Source ana = load(analysis_path);
    read_analysis(ana, to_si, s, velocity_of, out.notes);
    if (joint_types > static_cast<int>(s.interfaces.size()))
      throw SceneReadError(geometry_path + ": a <Joint> of type " + std::to_string(joint_types) + ", but " +
                           analysis_path + " gives " + std::to_string(s.interfaces.size()) + " <Jointproperties>");
  } else {
    placeholder_analysis(s, velocity_of, joint_types, out.notes);
  }

  std::string problem;
  const JointCut cut = cut_joint_lines(g.joints, problem);
  if (!problem.empty()) throw SceneReadError(geometry_path + ": " + problem);
  if (cut.blocks.empty()) throw SceneReadError(geometry_path + ": the joint lines close no block");
  if (cut.dropped_dangling > 0)
    out.notes.push_back(std::to_string(cut.dropped_dangling) + " dangling joint pieces dropped (they close no block)");
  std::vector<char> kept(cut.blocks.size(), 1);
  for (const Located& h : g.holes) {
    std::vector<BlockInput> probe(cut.blocks.size());
    for (size_t b = 0; b < cut.blocks.size(); ++b) probe[b].polygon = cut.blocks[b];
    const int b = block_containing(probe, h.a);
    if (b < 0) throw SceneReadError(geometry_path + ": line " + std::to_string(h.line) + ": <Point>: hole point in no block");
    kept[b] = 0;
  }
  std::vector<int> index_of(cut.blocks.size(), -1);
  for (size_t b = 0; b < cut.blocks.size(); ++b) {
    if (!kept[b]) continue;
    index_of[b] = static_cast<int>(s.blocks.size());
    BlockInput block;
    block.name = "block" + std::to_string(s.blocks.size() + 1);
    block.polygon = cut.blocks[b];
    block.material = 0;
    s.blocks.push_back(block);
  }
  // Materials: a material line gives its material to the blocks it crosses or starts in.
  for (const Located& m : g.material_lines) {
    if (m.type < 1 || m.type > static_cast<int>(s.materials.size()))
      throw SceneReadError(geometry_path + ": line " + std::to_string(m.line) + ": <Line type=\"" + std::to_string(m.type) +
                           "\">: no such block material (" + std::to_string(s.materials.size()) + " given)");
    for (BlockInput& b : s.blocks) {
      bool hit = point_in_polygon(m.a, b.polygon);
      for (int k = 1; k < 64 && !hit; ++k) hit = point_in_polygon(m.a + (k / 64.0) * (m.b - m.a), b.polygon);
      if (hit) b.material = m.type - 1;
    }
  }
  for (BlockInput& b : s.blocks) {
    const Vec3& v = velocity_of[b.material];
    b.velocity = Vec2(v[0], v[1]);
    b.angular_velocity = v[2];
  }
  // Fixed points: two or more fix a block; a fixed line fixes every block it crosses.
  std::vector<int> fixed_count(s.blocks.size(), 0), fixed_line(s.blocks.size(), 0);
  for (const Located& f : g.fixed) {
    if (f.a == f.b) {
      const int b = block_containing(s.blocks, f.a);
      if (b < 0) throw SceneReadError(geometry_path + ": line " + std::to_string(f.line) + ": <Point>: fixed point in no block");
      if (++fixed_count[b] == 1) fixed_line[b] = f.line;
      continue;
    }
    for (int k = 0; k <= 64; ++k) {
      const int b = block_containing(s.blocks, f.a + (k / 64.0) * (f.b - f.a));
      if (b >= 0) fixed_count[b] = std::max(fixed_count[b], 2);
    }
  }
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    if (fixed_count[b] == 1)
      throw SceneReadError(geometry_path + ": line " + std::to_string(fixed_line[b]) +
                           ": <Point>: the only fixed point of its block, a pin; ddafit fixes whole blocks: give the "
                           "block a second fixed point or none");
    s.blocks[b].fixed = fixed_count[b] >= 2;
  }
  for (const Located& m : g.measured) {
    if (block_containing(s.blocks, m.a) < 0)
      throw SceneReadError(geometry_path + ": line " + std::to_string(m.line) + ": <Point>: measured point in no block");
    s.measure.push_back({std::to_string(s.measure.size() + 1), m.a});
  }
  // Interfaces: one joint type throughout is the default; with several, each block is its
  // own group and the pairs touching at t = 0 across another type get a rule.
  std::map<int, int> type_count;
  for (const JointCut::SharedEdge& e : cut.shared)
    if (index_of[e.block_a] >= 0 && index_of[e.block_b] >= 0) ++type_count[e.type];
  int common = 1;
  for (const auto& [type, count] : type_count)
    if (count > type_count[common]) common = type;
  s.default_interface = common - 1;
  if (type_count.size() > 1) {
    for (BlockInput& b : s.blocks) b.group = b.name;
    for (const JointCut::SharedEdge& e : cut.shared) {
      const int a = index_of[e.block_a], b = index_of[e.block_b];
      if (a < 0 || b < 0 || e.type == common) continue;
      s.contact_rules.push_back({s.blocks[a].name, s.blocks[b].name, e.type - 1});
    }
    out.notes.push_back("joints of " + std::to_string(type_count.size()) + " types: blocks touching at t = 0 take the "
                        "type of the joint between them; blocks that meet later take joint" + std::to_string(common) +
                        " (the DDA codes take the type of the edge contacted)");
  }
  return out;
}

}  // namespace ddafit::io
