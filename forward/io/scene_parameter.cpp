// The key -> setter table of study parameters (scene_parameter.hpp). Each row sets one
// number of a Scene; the checks of the values themselves are the reader's own
// (validate_scene, validate_mesh_settings), run once after every parameter is set.
#include "forward/io/scene_parameter.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <type_traits>
#include <variant>

#include "forward/io/scene_reader.hpp"
#include "forward/io/yaml_checks.hpp"
#include "forward/mesh/region.hpp"

namespace ddafit::io {
namespace {

enum class Entry { None, Material, Interface };

struct Row {
  const char* section;  // first part of the key ("" for a top-level key)
  const char* field;    // last part
  Entry entry;          // Material / Interface: the key is SECTION.NAME.FIELD
  bool recut;           // a mesh setting: cut the regions again
  // Sets the value; returns a problem ("must be ...") or nullptr.
  const char* (*set)(Scene& s, int entry, double v);
};

// i = p/100 * phi_p (scene_reader.hpp): a percentage-given roughness follows the peak angle.
void keep_roughness_in_step(Interface& f) {
  if (f.degradation_percent) f.roughness_angle = *f.degradation_percent / 100.0 * f.friction_angle;
}

const Row kRows[] = {
    {"time", "duration", Entry::None, false, [](Scene& s, int, double v) -> const char* { return s.duration = v, nullptr; }},
    {"time", "step", Entry::None, false, [](Scene& s, int, double v) -> const char* { return s.max_step = v, nullptr; }},
    {"output", "interval", Entry::None, false,
     [](Scene& s, int, double v) -> const char* { return s.output_interval = v, nullptr; }},
    {"", "rest_speed", Entry::None, false, [](Scene& s, int, double v) -> const char* { return s.rest_speed = v, nullptr; }},
    {"materials", "density", Entry::Material, false,
     [](Scene& s, int k, double v) -> const char* { return s.materials[k].density = v, nullptr; }},
    {"materials", "young_modulus", Entry::Material, false,
     [](Scene& s, int k, double v) -> const char* { return s.materials[k].young_modulus = v, nullptr; }},
    {"materials", "poisson_ratio", Entry::Material, false,
     [](Scene& s, int k, double v) -> const char* { return s.materials[k].poisson_ratio = v, nullptr; }},
    {"interfaces", "friction_angle", Entry::Interface, false,
     [](Scene& s, int k, double v) -> const char* {
       s.interfaces[k].friction_angle = v;
       keep_roughness_in_step(s.interfaces[k]);
       return nullptr;
     }},
    {"interfaces", "cohesion", Entry::Interface, false,
     [](Scene& s, int k, double v) -> const char* { return s.interfaces[k].cohesion = v, nullptr; }},
    {"interfaces", "tensile_strength", Entry::Interface, false,
     [](Scene& s, int k, double v) -> const char* { return s.interfaces[k].tensile_strength = v, nullptr; }},
    {"interfaces", "roughness_angle", Entry::Interface, false,
     [](Scene& s, int k, double v) -> const char* {
       s.interfaces[k].roughness_angle = v;  // given in degrees: no longer a share of phi_p
       s.interfaces[k].degradation_percent.reset();
       return nullptr;
     }},
    {"interfaces", "degradation_percent", Entry::Interface, false,
     [](Scene& s, int k, double v) -> const char* {
       if (!(v >= 0.0 && v <= 100.0)) return "must be in [0, 100]";
       s.interfaces[k].degradation_percent = v;
       keep_roughness_in_step(s.interfaces[k]);
       return nullptr;
     }},
    {"interfaces", "critical_distance_ratio", Entry::Interface, false,
     [](Scene& s, int k, double v) -> const char* { return s.interfaces[k].critical_distance_ratio = v, nullptr; }},
    {"interfaces", "weakening_velocity", Entry::Interface, false,
     [](Scene& s, int k, double v) -> const char* {
       if (s.interfaces[k].law != FrictionLaw::VelocityWeakening) return "is read only by law: velocity_weakening";
       return s.interfaces[k].weakening_velocity = v, nullptr;
     }},
#define DDAFIT_BAND_ROW(FIELD)                                                                        \
  {"interfaces", #FIELD, Entry::Interface, false, [](Scene& s, int k, double v) -> const char* {     \
     if (s.interfaces[k].law != FrictionLaw::ThermalPressurization)                                  \
       return "is read only by law: thermal_pressurization";                                          \
     return s.interfaces[k].FIELD = v, nullptr;                                                       \
   }}
    DDAFIT_BAND_ROW(band_thickness),
    DDAFIT_BAND_ROW(heat_capacity),
    DDAFIT_BAND_ROW(pressurization_factor),
    DDAFIT_BAND_ROW(thermal_diffusivity),
    DDAFIT_BAND_ROW(hydraulic_diffusivity),
#undef DDAFIT_BAND_ROW
    {"earthquake", "scale", Entry::None, false,
     [](Scene& s, int, double v) -> const char* {
       if (!s.earthquake.present()) return "needs an earthquake: record in the scene";
       return s.earthquake.scale = v, nullptr;
     }},
    {"mesh", "block_size", Entry::None, true,
     [](Scene& s, int, double v) -> const char* {
       if (!(v > 0.0)) return "must be in (0, 1e6] m";  // 0 means "unset" only in a file
       return s.mesh.block_size = v, nullptr;
     }},
    {"mesh", "min_area_ratio", Entry::None, true,
     [](Scene& s, int, double v) -> const char* { return s.mesh.min_area_ratio = v, nullptr; }},
    {"mesh", "min_angle", Entry::None, true,
     [](Scene& s, int, double v) -> const char* { return s.mesh.min_angle = v, nullptr; }},
    {"mesh", "min_edge_ratio", Entry::None, true,
     [](Scene& s, int, double v) -> const char* { return s.mesh.min_edge_ratio = v, nullptr; }},
    {"mesh", "max_arrangement_edges", Entry::None, true,
     [](Scene& s, int, double v) -> const char* { return s.mesh.max_arrangement_edges = v, nullptr; }},
};
constexpr int kRowCount = static_cast<int>(std::size(kRows));
constexpr int kControlRow = kRowCount;  // time.substeps and control.NAME: from kControlKeys

std::string row_key(const Row& r) {
  std::string key = r.section;
  if (r.entry != Entry::None) key += ".NAME";
  return (key.empty() ? "" : key + ".") + r.field;
}

std::string text_of(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

template <class T>
int index_of(const std::vector<T>& items, const std::string& name) {
  for (size_t k = 0; k < items.size(); ++k)
    if (items[k].name == name) return static_cast<int>(k);
  return -1;
}

bool is_whole(double v) {
  return std::isfinite(v) && v == std::floor(v) && std::abs(v) <= std::numeric_limits<int>::max();
}

}  // namespace

std::vector<std::string> settable_keys() {
  std::vector<std::string> keys;
  for (const Row& r : kRows) keys.push_back(row_key(r));
  keys.push_back("time.substeps");
  for (const ControlKey& c : kControlKeys)
    if (!std::holds_alternative<bool SimulationOptions::*>(c.field)) keys.push_back(std::string("control.") + c.name);
  return keys;
}

SceneParameter::SceneParameter(const Scene& scene, const std::string& key, const std::string& file)
    : key_(key), file_(file) {
  const auto fail = [&](const std::string& problem) { throw SceneReadError(file + ": " + key + ": " + problem); };
  const size_t first = key.find('.'), last = key.rfind('.');
  const std::string section = first == std::string::npos ? "" : key.substr(0, first);
  const std::string field = last == std::string::npos ? key : key.substr(last + 1);
  const std::string name = first < last ? key.substr(first + 1, last - first - 1) : "";
  if (key == "time.substeps") {
    row_ = kControlRow;
    return;
  }
  if (section == "control" && name.empty()) {
    for (int c = 0; c < static_cast<int>(std::size(kControlKeys)); ++c)
      if (field == kControlKeys[c].name) {
        if (std::holds_alternative<bool SimulationOptions::*>(kControlKeys[c].field))
          fail("is a switch (true or false), not a number; set it under the study's settings");
        row_ = kControlRow;
        control_ = c;
        return;
      }
  }
  for (int r = 0; r < kRowCount; ++r) {
    const Row& row = kRows[r];
    if (section != row.section || field != row.field || (row.entry != Entry::None) == name.empty()) continue;
    row_ = r;
    if (row.entry == Entry::Material && (entry_ = index_of(scene.materials, name)) < 0)
      fail("the scene has no material '" + name + "' (it has: " + list_names(scene.materials) + ")");
    if (row.entry == Entry::Interface && (entry_ = index_of(scene.interfaces, name)) < 0)
      fail("the scene has no interface '" + name + "' (it has: " + list_names(scene.interfaces) + ")");
    return;
  }
  // The keys of the same section when there are any (a misspelt field), else all of them.
  std::string keys, all;
  for (const std::string& k : settable_keys()) {
    all += (all.empty() ? "" : ", ") + k;
    if (!section.empty() && k.rfind(section + ".", 0) == 0) keys += (keys.empty() ? "" : ", ") + k;
  }
  fail("not a number a study can set; use one of: " + (keys.empty() ? all : keys));
}

bool SceneParameter::recuts_blocks() const { return row_ >= 0 && row_ < kRowCount && kRows[row_].recut; }

void SceneParameter::set(Scene& scene, double value) const {
  const auto fail = [&](const std::string& problem) {
    throw SceneReadError(file_ + ": " + key_ + ": is " + text_of(value) + "; " + problem);
  };
  if (!std::isfinite(value)) fail("expected a finite number");
  if (row_ < kRowCount) {
    if (const char* problem = kRows[row_].set(scene, entry_, value)) fail(problem);
    return;
  }
  if (control_ < 0) {  // time.substeps
    if (!is_whole(value)) fail("expected a whole number");
    scene.options.substeps = static_cast<int>(value);
    return;
  }
  std::visit(
      [&](auto member) {
        using T = std::remove_reference_t<decltype(scene.options.*member)>;
        if constexpr (std::is_same_v<T, int>) {
          if (!is_whole(value)) fail("expected a whole number");
          scene.options.*member = static_cast<int>(value);
        } else if constexpr (std::is_same_v<T, double>) {
          scene.options.*member = value;
        }
      },
      kControlKeys[control_].field);
}

void set_parameters(Scene& scene, const std::vector<SceneParameter>& parameters, const std::vector<double>& values) {
  if (parameters.empty()) return;
  const std::string file = parameters.front().file_label();
  bool recut = false;
  for (size_t k = 0; k < parameters.size() && k < values.size(); ++k) {
    parameters[k].set(scene, values[k]);
    recut = recut || parameters[k].recuts_blocks();
  }
  const auto fail = [&](const std::string& key, const std::string& problem) {
    throw SceneReadError(file + ": " + key + ": " + problem);
  };
  if (recut) for (const SceneError& e : validate_mesh_settings(scene.mesh)) fail(e.key, e.problem);
  if (recut && !scene.regions.empty()) {
    std::string problem;
    generate_blocks(scene, problem);
    if (!problem.empty()) fail(problem.substr(0, problem.find(':')), problem.substr(problem.find(':') + 2));
  }
  const std::vector<SceneError> errors = validate_scene(scene);
  if (!errors.empty()) fail(errors.front().key, errors.front().problem);
}

}  // namespace ddafit::io
