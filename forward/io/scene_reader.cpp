// Reads scene files (format: scene_reader.hpp) into a checked Scene. The writer,
// scene_to_yaml(), is in scene_writer.cpp.
#include "forward/io/scene_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

namespace ddafit::io {

namespace {

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string indexed(const std::string& path, size_t k) {
  return path + "[" + std::to_string(k) + "]";
}

template <class T>
std::string list_names(const std::vector<T>& items) {
  std::string out;
  for (const T& item : items) out += (out.empty() ? "" : ", ") + item.name;
  return out.empty() ? "none" : out;
}

// Parses one YAML tree into a Scene; every failure throws "FILE: KEY: PROBLEM".
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  Scene read(const YAML::Node& root) const {
    if (!root.IsMap()) fail("(top level)", "expected a map of scene keys (time, materials, ...)");
    check_keys(root, "", {"gravity", "time", "materials", "interfaces", "blocks", "contacts",
                          "default_interface", "measure", "output", "rest_speed", "control"});
    Scene s;
    if (const YAML::Node n = root["gravity"]) s.gravity = vec2(n, "gravity");
    const YAML::Node time = required(root, "", "time", "add time: {duration: ..., step: ...}");
    check_keys(time, "time", {"duration", "step"});
    s.duration = req_number(time, "time", "duration", "give the end time in s");
    s.max_step = req_number(time, "time", "step", "give the time step in s");
    read_materials(required(root, "", "materials", "define at least one material"), s);
    if (const YAML::Node n = root["interfaces"]) read_interfaces(n, s);
    read_blocks(required(root, "", "blocks", "define at least one block"), s);
    if (const YAML::Node n = root["contacts"]) read_contacts(n, s);
    if (const YAML::Node n = root["default_interface"]) {
      s.default_interface =
          find(s.interfaces, text(n, "default_interface"), "default_interface", "interface");
    } else if (s.interfaces.size() == 1) {
      // A single interface means "use it everywhere". With several and no default the
      // index stays -1 and the physics reports any touching group pair without a rule.
      s.default_interface = 0;
    }
    if (const YAML::Node n = root["measure"]) read_measure(n, s);
    if (const YAML::Node n = root["output"]) {
      check_keys(n, "output", {"interval"});
      opt_number(n, "output", "interval", s.output_interval);
    }
    opt_number(root, "", "rest_speed", s.rest_speed);
    if (const YAML::Node n = root["control"]) read_control(n, s.options);

    const std::vector<SceneError> errors = validate_scene(s);
    if (!errors.empty()) fail(errors.front().key, errors.front().problem);
    return s;
  }

 private:
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw SceneReadError(file_ + ": " + key + ": " + problem);
  }

  // Keys of a map, rejecting repeats, which yaml-cpp would otherwise keep silently.
  std::vector<std::string> map_keys(const YAML::Node& node, const std::string& path) const {
    if (!node.IsMap()) fail(path, "expected a map {key: value, ...}");
    std::vector<std::string> keys;
    std::set<std::string> seen;
    for (const auto& kv : node) {
      if (!kv.first.IsScalar())
        fail(path.empty() ? "(top level)" : path, "expected plain names as keys");
      keys.push_back(kv.first.Scalar());
      if (!seen.insert(keys.back()).second) fail(join(path, keys.back()), "given twice; keep one");
    }
    return keys;
  }

  // Rejects keys outside `allowed`: the usual symptom of a misspelling.
  void check_keys(const YAML::Node& node, const std::string& path,
                  const std::vector<std::string>& allowed) const {
    for (const std::string& key : map_keys(node, path)) {
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(join(path, key), "unknown key; allowed keys: " + list);
    }
  }

  YAML::Node required(const YAML::Node& map, const std::string& path, const char* key,
                      const std::string& hint) const {
    const YAML::Node n = map[key];
    if (!n) fail(join(path, key), "missing required key; " + hint);
    return n;
  }

  template <class T>
  T scalar(const YAML::Node& node, const std::string& path, const char* what) const {
    if (!node.IsScalar()) fail(path, std::string("expected ") + what);
    try {
      return node.as<T>();
    } catch (const YAML::BadConversion&) {
      fail(path, std::string("expected ") + what + ", got '" + node.Scalar() + "'");
    }
  }
  double number(const YAML::Node& n, const std::string& path) const {
    return scalar<double>(n, path, "a number");
  }
  std::string text(const YAML::Node& n, const std::string& path) const {
    return scalar<std::string>(n, path, "a name");
  }
  Vec2 vec2(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence() || n.size() != 2) fail(path, "expected a pair of numbers [x, y]");
    return Vec2(number(n[0], indexed(path, 0)), number(n[1], indexed(path, 1)));
  }
  double req_number(const YAML::Node& map, const std::string& path, const char* key,
                    const char* hint) const {
    return number(required(map, path, key, hint), join(path, key));
  }
  void opt_number(const YAML::Node& map, const std::string& path, const char* key,
                  double& target) const {
    if (const YAML::Node n = map[key]) target = number(n, join(path, key));
  }
  void list(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence()) fail(path, "expected a list [...]");
  }

  template <class T>
  int find(const std::vector<T>& items, const std::string& name, const std::string& path,
           const char* what) const {
    for (size_t k = 0; k < items.size(); ++k)
      if (items[k].name == name) return static_cast<int>(k);
    fail(path, std::string("unknown ") + what + " '" + name + "'; defined: " + list_names(items));
  }

  void read_materials(const YAML::Node& node, Scene& s) const {
    const std::vector<std::string> names = map_keys(node, "materials");
    if (names.empty()) fail("materials", "is empty; define at least one material");
    for (const std::string& name : names) {
      const std::string path = "materials." + name;
      const YAML::Node m = node[name];
      check_keys(m, path, {"density", "young_modulus", "poisson_ratio"});
      s.materials.push_back({name, req_number(m, path, "density", "give kg/m^3"),
                             req_number(m, path, "young_modulus", "give Pa"),
                             req_number(m, path, "poisson_ratio", "give a value in [0, 0.5)")});
    }
  }

  void read_interfaces(const YAML::Node& node, Scene& s) const {
    for (const std::string& name : map_keys(node, "interfaces")) {
      const std::string path = "interfaces." + name;
      const YAML::Node f = node[name];
      check_keys(f, path, {"friction_angle", "cohesion", "tensile_strength", "roughness_angle",
                           "degradation_percent", "critical_distance_ratio"});
      Interface in;
      in.name = name;
      in.friction_angle = req_number(f, path, "friction_angle", "give degrees");
      opt_number(f, path, "cohesion", in.cohesion);
      opt_number(f, path, "tensile_strength", in.tensile_strength);
      opt_number(f, path, "critical_distance_ratio", in.critical_distance_ratio);
      opt_number(f, path, "roughness_angle", in.roughness_angle);
      if (const YAML::Node n = f["degradation_percent"]) {
        if (f["roughness_angle"])
          fail(path, "give either roughness_angle or degradation_percent, not both");
        // Roughness as the share of the peak angle lost on full degradation:
        // i = p/100 * phi_p, so the residual angle is phi_b = (1 - p/100) * phi_p.
        const double p = number(n, path + ".degradation_percent");
        if (!(p >= 0 && p <= 100))
          fail(path + ".degradation_percent", "is " + n.Scalar() + "; must be in [0, 100]");
        in.roughness_angle = p / 100.0 * in.friction_angle;
      }
      s.interfaces.push_back(in);
    }
  }

  void read_blocks(const YAML::Node& node, Scene& s) const {
    if (!node.IsSequence() || node.size() == 0)
      fail("blocks", "expected a non-empty list of blocks");
    for (size_t k = 0; k < node.size(); ++k) {
      const std::string path = indexed("blocks", k);
      const YAML::Node b = node[k];
      check_keys(b, path, {"name", "group", "material", "fixed", "polygon", "velocity",
                           "angular_velocity"});
      BlockInput block;
      block.name = text(required(b, path, "name", "give a unique name"), path + ".name");
      block.group = block.name;
      if (const YAML::Node n = b["group"]) block.group = text(n, path + ".group");
      const std::string material =
          text(required(b, path, "material", "name a material"), path + ".material");
      block.material = find(s.materials, material, path + ".material", "material");
      if (const YAML::Node n = b["fixed"])
        block.fixed = scalar<bool>(n, path + ".fixed", "true or false");
      const std::string poly_path = path + ".polygon";
      const YAML::Node poly = required(b, path, "polygon", "give [[x, y], ...]");
      list(poly, poly_path);
      for (size_t i = 0; i < poly.size(); ++i)
        block.polygon.push_back(vec2(poly[i], indexed(poly_path, i)));
      if (const YAML::Node n = b["velocity"]) block.velocity = vec2(n, path + ".velocity");
      opt_number(b, path, "angular_velocity", block.angular_velocity);
      s.blocks.push_back(std::move(block));
    }
  }

  void read_contacts(const YAML::Node& node, Scene& s) const {
    std::set<std::string> groups;
    for (const BlockInput& b : s.blocks) groups.insert(b.group);
    list(node, "contacts");
    for (size_t k = 0; k < node.size(); ++k) {
      const std::string path = indexed("contacts", k);
      const YAML::Node c = node[k];
      check_keys(c, path, {"between", "interface"});
      const YAML::Node between = required(c, path, "between", "give [group_a, group_b]");
      if (!between.IsSequence() || between.size() != 2)
        fail(path + ".between", "expected two group names [group_a, group_b]");
      ContactRule rule;
      rule.group_a = text(between[0], path + ".between[0]");
      rule.group_b = text(between[1], path + ".between[1]");
      for (const std::string& g : {rule.group_a, rule.group_b})
        if (!groups.count(g))
          fail(path + ".between",
               "unknown group '" + g + "'; no block has it (group defaults to the block name)");
      const std::string name =
          text(required(c, path, "interface", "name an interface"), path + ".interface");
      rule.interface = find(s.interfaces, name, path + ".interface", "interface");
      s.contact_rules.push_back(rule);
    }
  }

  void read_measure(const YAML::Node& node, Scene& s) const {
    list(node, "measure");
    for (size_t k = 0; k < node.size(); ++k) {
      const std::string path = indexed("measure", k);
      const YAML::Node m = node[k];
      check_keys(m, path, {"name", "at"});
      MeasurePoint point;
      point.name = text(required(m, path, "name", "give a unique name"), path + ".name");
      point.at = vec2(required(m, path, "at", "give [x, y]"), path + ".at");
      s.measure.push_back(point);
    }
  }

  void read_control(const YAML::Node& node, SimulationOptions& o) const {
    std::vector<std::string> allowed;
    for (const ControlKey& f : kControlKeys) allowed.push_back(f.name);
    check_keys(node, "control", allowed);
    for (const ControlKey& f : kControlKeys) {
      const YAML::Node n = node[f.name];
      if (!n) continue;
      const std::string path = std::string("control.") + f.name;
      std::visit(
          [&](auto member) {
            using T = std::remove_reference_t<decltype(o.*member)>;
            if constexpr (std::is_same_v<T, double>)
              o.*member = number(n, path);
            else if constexpr (std::is_same_v<T, int>)
              o.*member = scalar<int>(n, path, "a whole number");
            else
              o.*member = scalar<bool>(n, path, "true or false");
          },
          f.field);
    }
  }

  std::string file_;
};

std::string yaml_error(const std::string& label, const YAML::Exception& e, const char* what) {
  const std::string where =
      e.mark.is_null() ? std::string("(unknown position)")
                       : "line " + std::to_string(e.mark.line + 1) + ", column " +
                             std::to_string(e.mark.column + 1);
  return label + ": " + where + ": " + what + e.msg;
}

}  // namespace

Scene parse_scene(const std::string& yaml_text, const std::string& file_label) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw SceneReadError(yaml_error(file_label, e, "malformed YAML: "));
  }
  try {
    return Reader(file_label).read(root);
  } catch (const YAML::Exception& e) {
    // Safety net: the reader checks node types before converting, so this is unexpected.
    throw SceneReadError(yaml_error(file_label, e, ""));
  }
}

Scene read_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in) throw SceneReadError(path + ": cannot read the file: " + std::strerror(errno));
  return parse_scene(text.str(), path);
}

}  // namespace ddafit::io
