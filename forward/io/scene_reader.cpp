// Reads scene files (format: scene_reader.hpp) into a checked Scene. The writer,
// scene_to_yaml(), is in scene_writer.cpp.
#include "forward/io/scene_reader.hpp"
#include "forward/io/region_reader.hpp"
#include "forward/io/water_reader.hpp"
#include "forward/io/earthquake_reader.hpp"
#include "forward/io/text_input.hpp"
#include "forward/io/yaml_checks.hpp"
#include "forward/mesh/region.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

namespace ddafit::io {

namespace {

// Parses one YAML tree into a Scene; every failure throws "FILE: KEY: PROBLEM".
class Reader : public YamlChecks {
 public:
  Reader(std::string file, std::string base_dir) : YamlChecks(std::move(file)), base_dir_(std::move(base_dir)) {}

  Scene read(const YAML::Node& root) const {
    if (!root.IsMap()) fail("(top level)", "expected a map of scene keys (time, materials, ...)");
    check_keys(root, "", {"gravity", "time", "materials", "interfaces", "blocks", "contacts",
                          "default_interface", "measure", "output", "rest_speed", "control", "mesh",
                          "regions", "water", "earthquake"});  // "base" is resolved before reading (load_tree)
    Scene s;
    if (const YAML::Node n = root["gravity"]) s.gravity = vec2(n, "gravity");
    const YAML::Node time = required(root, "", "time", "add time: {duration: ..., step: ...}");
    check_keys(time, "time", {"duration", "step", "integrator", "substeps"});
    s.duration = req_number(time, "time", "duration", "give the end time in s");
    s.max_step = req_number(time, "time", "step", "give the time step in s");
    if (const YAML::Node n = time["integrator"]) s.options.integrator = integrator(n);
    if (const YAML::Node n = time["substeps"]) s.options.substeps = scalar<int>(n, "time.substeps", "a whole number");
    read_materials(required(root, "", "materials", "define at least one material"), s);
    if (const YAML::Node n = root["interfaces"]) read_interfaces(n, s);
    if (const YAML::Node b = root["blocks"]; b || !root["regions"])
      read_blocks(required(root, "", "blocks", "define at least one block (or regions)"), s);
    read_regions(*this, root, base_dir_, s);
    if (!s.regions.empty()) {
      std::string problem;
      generate_blocks(s, problem);
      if (!problem.empty()) fail(problem.substr(0, problem.find(':')), problem.substr(problem.find(':') + 2));
    }
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
    if (const YAML::Node n = root["water"]) read_water(*this, n, base_dir_, s);
    if (const YAML::Node n = root["earthquake"]) read_earthquake(*this, n, base_dir_, s);
    if (const YAML::Node n = root["control"]) read_control(n, s.options);

    const std::vector<SceneError> errors = validate_scene(s);
    if (!errors.empty()) fail(errors.front().key, errors.front().problem);
    return s;
  }

 private:
  FrictionLaw friction_law(const YAML::Node& n, const std::string& key) const {
    const std::string name = text(n, key);
    for (FrictionLaw law : kFrictionLaws)
      if (name == to_string(law)) return law;
    fail(key, "is '" + name + "'; use bilinear, exponential, velocity_weakening or thermal_pressurization");
  }

  Integrator integrator(const YAML::Node& n) const {
    const std::string name = text(n, "time.integrator");
    for (Integrator i : {Integrator::Implicit, Integrator::Substep, Integrator::Auto, Integrator::Sled})
      if (name == to_string(i)) return i;
    fail("time.integrator", "is '" + name + "'; use implicit, substep, auto or sled");
  }

  void read_materials(const YAML::Node& node, Scene& s) const {
    const std::vector<std::string> names = map_keys(node, "materials");
    if (names.empty()) fail("materials", "is empty; define at least one material");
    for (const std::string& name : names) {
      const std::string path = "materials." + name;
      const YAML::Node m = node[name];
      check_keys(m, path, {"density", "young_modulus", "poisson_ratio", "rigid"});
      s.materials.push_back({name, req_number(m, path, "density", "give kg/m^3"),
                             req_number(m, path, "young_modulus", "give Pa"),
                             req_number(m, path, "poisson_ratio", "give a value in [0, 0.5)")});
      if (const YAML::Node n = m["rigid"]) s.materials.back().rigid = scalar<bool>(n, path + ".rigid", "true or false");
    }
  }

  void read_interfaces(const YAML::Node& node, Scene& s) const {
    for (const std::string& name : map_keys(node, "interfaces")) {
      const std::string path = "interfaces." + name;
      const YAML::Node f = node[name];
      check_keys(f, path, {"friction_angle", "cohesion", "tensile_strength", "roughness_angle",
                           "degradation_percent", "critical_distance_ratio", "law", "weakening_velocity",
                           "band_thickness", "heat_capacity", "pressurization_factor", "thermal_diffusivity",
                           "hydraulic_diffusivity"});
      Interface in;
      in.name = name;
      in.friction_angle = req_number(f, path, "friction_angle", "give degrees");
      opt_number(f, path, "cohesion", in.cohesion);
      opt_number(f, path, "tensile_strength", in.tensile_strength);
      opt_number(f, path, "critical_distance_ratio", in.critical_distance_ratio);
      opt_number(f, path, "roughness_angle", in.roughness_angle);
      if (const YAML::Node n = f["law"]) in.law = friction_law(n, path + ".law");
      opt_number(f, path, "weakening_velocity", in.weakening_velocity);
      if (f["weakening_velocity"] && in.law != FrictionLaw::VelocityWeakening)
        fail(path + ".weakening_velocity", "is read only by law: velocity_weakening (this interface's law is " +
                                               std::string(to_string(in.law)) + ")");
      // The shear band of law: thermal_pressurization.
      const std::pair<const char*, double Interface::*> band[] = {
          {"band_thickness", &Interface::band_thickness},
          {"heat_capacity", &Interface::heat_capacity},
          {"pressurization_factor", &Interface::pressurization_factor},
          {"thermal_diffusivity", &Interface::thermal_diffusivity},
          {"hydraulic_diffusivity", &Interface::hydraulic_diffusivity}};
      for (const auto& [name, field] : band) {
        if (!f[name]) continue;
        if (in.law != FrictionLaw::ThermalPressurization)
          fail(path + "." + name, "is read only by law: thermal_pressurization (this interface's law is " +
                                      std::string(to_string(in.law)) + ")");
        in.*field = number(f[name], path + "." + name);
      }
      if (const YAML::Node n = f["degradation_percent"]) {
        if (f["roughness_angle"])
          fail(path, "give either roughness_angle or degradation_percent, not both");
        // Roughness as the share of the peak angle lost on full degradation:
        // i = p/100 * phi_p, so the residual angle is phi_b = (1 - p/100) * phi_p.
        const double p = number(n, path + ".degradation_percent");
        if (!(p >= 0 && p <= 100))
          fail(path + ".degradation_percent", "is " + n.Scalar() + "; must be in [0, 100]");
        in.degradation_percent = p;
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

  std::string base_dir_;  // where relative CSV paths start
};

std::string yaml_error(const std::string& label, const YAML::Exception& e, const char* what) {
  const std::string where =
      e.mark.is_null() ? std::string("(unknown position)")
                       : "line " + std::to_string(e.mark.line + 1) + ", column " +
                             std::to_string(e.mark.column + 1);
  return label + ": " + where + ": " + what + e.msg;
}


}  // namespace

// Deep merge for `base:`: maps merge key by key, anything else replaces.
void merge_into(YAML::Node target, const YAML::Node& source);

namespace {

// Loads a scene tree, following `base:` (a scene this one inherits and overrides).
YAML::Node load_tree(const std::string& yaml_text, const std::string& file_label, const std::string& base_dir,
                     int depth) {
  YAML::Node root;
  try {
    if (yaml_document_count(yaml_text) > 1)
      throw SceneReadError(file_label + ": (top level): the file holds more than one YAML document (a '---' line "
                           "starts another, and everything after it would be ignored); keep one");
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw SceneReadError(yaml_error(file_label, e, "malformed YAML: "));
  }
  if (!root.IsMap() || !root["base"]) return root;
  if (depth > 8) throw SceneReadError(file_label + ": base: scenes inherit each other in a loop");
  if (!root["base"].IsScalar()) throw SceneReadError(file_label + ": base: expected a scene file name");
  std::filesystem::path base_path(root["base"].Scalar());
  if (base_path.is_relative() && !base_dir.empty()) base_path = std::filesystem::path(base_dir) / base_path;
  std::string problem;
  const std::string text = read_input_file(base_path.string(), problem);
  if (!problem.empty()) throw SceneReadError(file_label + ": base: " + problem);
  YAML::Node merged = load_tree(text, base_path.string(), base_path.parent_path().string(), depth + 1);
  root.remove("base");
  merge_into(merged, root);
  return merged;
}

}  // namespace

void merge_into(YAML::Node target, const YAML::Node& source) {
  for (const auto& entry : source) {
    const std::string key = entry.first.Scalar();
    if (entry.second.IsMap() && target[key] && target[key].IsMap())
      merge_into(target[key], entry.second);
    else
      target[key] = YAML::Clone(entry.second);
  }
}

Scene parse_scene(const std::string& yaml_text, const std::string& file_label, const std::string& base_dir,
                  const std::vector<std::pair<std::string, std::string>>& overrides) {
  YAML::Node root = load_tree(yaml_text, file_label, base_dir, 0);
  for (const auto& [key, value] : overrides) {
    // key "a.b.c" sets root[a][b][c]; the value is parsed as YAML ("25", "[1, 2]").
    if (!root.IsMap()) break;
    std::vector<std::string> parts;
    std::stringstream path(key);
    for (std::string part; std::getline(path, part, '.');) parts.push_back(part);
    YAML::Node parsed;
    try {
      parsed = YAML::Load(value);
    } catch (const YAML::Exception&) {
      throw SceneReadError(file_label + ": " + key + ": the value '" + value + "' is not valid YAML");
    }
    std::vector<YAML::Node> chain{root};
    for (size_t k = 0; k + 1 < parts.size(); ++k) {
      YAML::Node next = chain.back()[parts[k]];
      // A material or interface is named, not made: a misspelt name would otherwise add an
      // entry no block uses and leave the one meant unchanged.
      if (k == 1 && (parts[0] == "materials" || parts[0] == "interfaces") && !next.IsDefined()) {
        std::string names;
        for (const auto& entry : chain.back())
          if (entry.first.IsScalar()) names += (names.empty() ? "" : ", ") + entry.first.as<std::string>();
        throw SceneReadError(file_label + ": " + key + ": no " + (parts[0] == "materials" ? "material" : "interface") +
                             " '" + parts[1] + "' in the scene" + (names.empty() ? "" : " (it has: " + names + ")"));
      }
      // A section the scene does not have yet (control:, say) is created; the reader
      // then checks its keys as if the file had it.
      if (!next.IsDefined() || next.IsNull()) {
        chain.back()[parts[k]] = YAML::Node(YAML::NodeType::Map);
        next = chain.back()[parts[k]];
      }
      if (!next.IsMap()) throw SceneReadError(file_label + ": " + key + ": '" + parts[k] + "' is not a map in the scene");
      chain.push_back(next);
    }
    chain.back()[parts.back()] = parsed;
  }
  try {
    return Reader(file_label, base_dir).read(root);
  } catch (const YAML::Exception& e) {
    // Safety net: the reader checks node types before converting, so this is unexpected.
    throw SceneReadError(yaml_error(file_label, e, ""));
  }
}

Scene read_scene(const std::string& path, const std::vector<std::pair<std::string, std::string>>& overrides) {
  std::string problem;
  const std::string text = read_input_file(path, problem);
  if (!problem.empty()) throw SceneReadError(problem);
  return parse_scene(text, path, std::filesystem::path(path).parent_path().string(), overrides);
}

}  // namespace ddafit::io
