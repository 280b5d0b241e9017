// Writes a Scene in the format read by scene_reader.cpp, e.g. for meshes built by a
// generator. Numbers use the shortest text that reads back exactly.
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "forward/io/scene_reader.hpp"

namespace ddafit::io {

namespace {

// Shortest text that reads back as the same double (YAML spellings for inf and nan):
// written scenes stay readable and still round-trip exactly.
std::string number_text(double v) {
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

void put_vec2(YAML::Emitter& out, const Vec2& v) {
  out << YAML::Flow << YAML::BeginSeq << number_text(v.x()) << number_text(v.y())
      << YAML::EndSeq;
}

// A small map on one line, values already formatted.
void put_flow_map(YAML::Emitter& out, const std::vector<std::pair<std::string, std::string>>& kv) {
  out << YAML::Flow << YAML::BeginMap;
  for (const auto& [key, value] : kv) out << YAML::Key << key << YAML::Value << value;
  out << YAML::EndMap;
}

template <class T>
const std::string& name_of(const std::vector<T>& items, int index, const std::string& who) {
  if (index < 0 || index >= static_cast<int>(items.size()))
    throw std::invalid_argument("scene_to_yaml: " + who + " refers to a missing entry");
  return items[index].name;
}

}  // namespace

std::string scene_to_yaml(const Scene& s) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap, YAML::BeginSeq, YAML::EndSeq;
  const auto num = number_text;
  YAML::Emitter out;
  out << BeginMap << Key << "gravity" << Value;
  put_vec2(out, s.gravity);
  out << Key << "time" << Value;
  std::vector<std::pair<std::string, std::string>> time{{"duration", num(s.duration)}, {"step", num(s.max_step)}};
  const SimulationOptions default_options;
  if (s.options.integrator != default_options.integrator) time.emplace_back("integrator", to_string(s.options.integrator));
  if (s.options.substeps != default_options.substeps) time.emplace_back("substeps", std::to_string(s.options.substeps));
  put_flow_map(out, time);
  out << Key << "materials" << Value << BeginMap;
  for (const Material& m : s.materials) {
    out << Key << m.name << Value;
    std::vector<std::pair<std::string, std::string>> fields{{"density", num(m.density)},
                                                           {"young_modulus", num(m.young_modulus)},
                                                           {"poisson_ratio", num(m.poisson_ratio)}};
    if (m.rigid) fields.emplace_back("rigid", "true");
    put_flow_map(out, fields);
  }
  out << EndMap;
  if (!s.interfaces.empty()) {
    out << Key << "interfaces" << Value << BeginMap;
    for (const Interface& f : s.interfaces) {
      out << Key << f.name << Value;
      // The roughness as the scene gave it, so that a later change of the peak angle moves
      // a percentage-given roughness with it.
      std::vector<std::pair<std::string, std::string>> fields{
          {"friction_angle", num(f.friction_angle)},
          {"cohesion", num(f.cohesion)},
          {"tensile_strength", num(f.tensile_strength)},
          f.degradation_percent ? std::pair<std::string, std::string>("degradation_percent", num(*f.degradation_percent))
                                : std::pair<std::string, std::string>("roughness_angle", num(f.roughness_angle)),
          {"critical_distance_ratio", num(f.critical_distance_ratio)}};
      if (f.law != FrictionLaw::Bilinear) fields.emplace_back("law", to_string(f.law));
      if (f.law == FrictionLaw::VelocityWeakening) fields.emplace_back("weakening_velocity", num(f.weakening_velocity));
      if (f.law == FrictionLaw::ThermalPressurization) {
        fields.emplace_back("band_thickness", num(f.band_thickness));
        fields.emplace_back("heat_capacity", num(f.heat_capacity));
        fields.emplace_back("pressurization_factor", num(f.pressurization_factor));
        fields.emplace_back("thermal_diffusivity", num(f.thermal_diffusivity));
        fields.emplace_back("hydraulic_diffusivity", num(f.hydraulic_diffusivity));
      }
      put_flow_map(out, fields);
    }
    out << EndMap;
  }

  // One line per block; defaults are left out to keep generated meshes small.
  out << Key << "blocks" << Value << BeginSeq;
  for (size_t k = 0; k < s.blocks.size(); ++k) {
    const BlockInput& b = s.blocks[k];
    out << YAML::Flow << BeginMap << Key << "name" << Value << b.name;
    if (!b.group.empty() && b.group != b.name) out << Key << "group" << Value << b.group;
    const std::string who = "blocks[" + std::to_string(k) + "]";
    out << Key << "material" << Value << name_of(s.materials, b.material, who);
    if (b.fixed) out << Key << "fixed" << Value << true;
    out << Key << "polygon" << Value << BeginSeq;
    for (const Vec2& p : b.polygon) put_vec2(out, p);
    out << EndSeq;
    if (b.velocity != Vec2::Zero()) {
      out << Key << "velocity" << Value;
      put_vec2(out, b.velocity);
    }
    if (b.angular_velocity != 0.0)
      out << Key << "angular_velocity" << Value << num(b.angular_velocity);
    out << EndMap;
  }
  out << EndSeq;

  if (!s.contact_rules.empty()) {
    out << Key << "contacts" << Value << BeginSeq;
    for (size_t k = 0; k < s.contact_rules.size(); ++k) {
      const ContactRule& r = s.contact_rules[k];
      out << YAML::Flow << BeginMap << Key << "between" << Value << YAML::Flow << BeginSeq
          << r.group_a << r.group_b << EndSeq << Key << "interface" << Value
          << name_of(s.interfaces, r.interface, "contacts[" + std::to_string(k) + "]") << EndMap;
    }
    out << EndSeq;
  }
  // -1 with exactly one interface cannot be expressed: the reader then makes that
  // interface the default.
  if (s.default_interface >= 0)
    out << Key << "default_interface" << Value
        << name_of(s.interfaces, s.default_interface, "default_interface");
  if (!s.measure.empty()) {
    out << Key << "measure" << Value << BeginSeq;
    for (const MeasurePoint& m : s.measure) {
      out << YAML::Flow << BeginMap << Key << "name" << Value << m.name << Key << "at" << Value;
      put_vec2(out, m.at);
      out << EndMap;
    }
    out << EndSeq;
  }
  out << Key << "output" << Value;
  put_flow_map(out, {{"interval", num(s.output_interval)}});
  out << Key << "rest_speed" << Value << num(s.rest_speed);
  if (s.water.present()) {
    out << Key << "water" << Value << BeginMap;
    if (s.water.level) out << Key << "level" << Value << num(*s.water.level);
    if (!s.water.table.empty()) {
      out << Key << "table" << Value << YAML::Flow << BeginSeq;
      for (const Vec2& p : s.water.table) put_vec2(out, p);
      out << EndSeq;
    }
    out << Key << "density" << Value << num(s.water.density) << EndMap;
  }
  if (s.earthquake.present()) {
    // The record inline in m/s^2, unscaled, so that the file stands alone.
    const GroundMotion& g = s.earthquake;
    out << Key << "earthquake" << Value << BeginMap << Key << "units" << Value << "m/s2";
    out << Key << "scale" << Value << num(g.scale);
    out << Key << "record" << Value << BeginSeq;
    for (size_t k = 0; k < g.time.size(); ++k)
      out << YAML::Flow << BeginSeq << num(g.time[k]) << num(g.acceleration[k].x()) << num(g.acceleration[k].y())
          << EndSeq;
    out << EndSeq << EndMap;
  }

  // Only options that differ from the defaults, so the file shows what was tuned.
  const SimulationOptions defaults;
  std::vector<std::pair<std::string, std::string>> changed;
  for (const ControlKey& f : kControlKeys) {
    std::visit(
        [&](auto member) {
          const auto value = s.options.*member;
          if (value == defaults.*member) return;
          using T = std::remove_const_t<decltype(value)>;
          if constexpr (std::is_same_v<T, double>)
            changed.emplace_back(f.name, num(value));
          else if constexpr (std::is_same_v<T, int>)
            changed.emplace_back(f.name, std::to_string(value));
          else
            changed.emplace_back(f.name, value ? "true" : "false");
        },
        f.field);
  }
  if (!changed.empty()) {
    out << Key << "control" << Value;
    put_flow_map(out, changed);
  }
  out << EndMap;
  if (!out.good()) throw std::logic_error("scene_to_yaml: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

}  // namespace ddafit::io
