#include "python/scene_settings.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <map>
#include <type_traits>
#include <variant>

namespace py = pybind11;

namespace ddafit::python {
namespace {

// Every setting of the scene by its key in scene-file terms, with its value.
std::map<std::string, py::object> settings_of(const Scene& s) {
  std::map<std::string, py::object> out;
  out["time.duration"] = py::float_(s.duration);
  out["time.step"] = py::float_(s.max_step);
  out["time.integrator"] = py::str(to_string(s.options.integrator));
  out["time.substeps"] = py::int_(s.options.substeps);
  out["output.interval"] = py::float_(s.output_interval);
  out["rest_speed"] = py::float_(s.rest_speed);
  if (!s.regions.empty()) out["mesh.block_size"] = py::float_(s.mesh.block_size);
  for (const Material& m : s.materials) {
    const std::string k = "materials." + m.name + ".";
    out[k + "density"] = py::float_(m.density);
    out[k + "young_modulus"] = py::float_(m.young_modulus);
    out[k + "poisson_ratio"] = py::float_(m.poisson_ratio);
    out[k + "rigid"] = py::bool_(m.rigid);
  }
  for (const Interface& f : s.interfaces) {
    const std::string k = "interfaces." + f.name + ".";
    out[k + "law"] = py::str(to_string(f.law));
    out[k + "friction_angle"] = py::float_(f.friction_angle);
    out[k + "cohesion"] = py::float_(f.cohesion);
    out[k + "tensile_strength"] = py::float_(f.tensile_strength);
    out[k + "roughness_angle"] = py::float_(f.roughness_angle);
    if (f.degradation_percent) out[k + "degradation_percent"] = py::float_(*f.degradation_percent);
    out[k + "critical_distance_ratio"] = py::float_(f.critical_distance_ratio);
  }
  for (const io::ControlKey& c : io::kControlKeys)
    std::visit([&](auto field) { out[std::string("control.") + c.name] = py::cast(s.options.*field); }, c.field);
  return out;
}

}  // namespace

std::string setting_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  return py::str(value).cast<std::string>();
}

void bind_scene(py::module_& m) {
  py::class_<PyScene>(m, "Scene", "A scene read from its file, with the settings changed since (see docs/python.md)")
      .def_readonly("path", &PyScene::path)
      .def("__getitem__",
           [](const PyScene& s, const std::string& key) {
             const auto all = settings_of(s.scene);
             const auto it = all.find(key);
             if (it == all.end()) throw py::key_error(key + ": not a setting of this scene (see Scene.keys())");
             return it->second;
           })
      .def("__setitem__",
           [](PyScene& s, const std::string& key, const py::object& value) {
             io::Overrides changed = s.overrides;
             changed.emplace_back(key, setting_text(value));
             s.scene = io::read_scene(s.path, changed);  // throws (ValueError) and leaves s as it was
             s.overrides = changed;
           })
      .def("keys",
           [](const PyScene& s) {
             std::vector<std::string> keys;
             for (const auto& [k, v] : settings_of(s.scene)) keys.push_back(k);
             return keys;
           })
      .def("settings", [](const PyScene& s) { return settings_of(s.scene); }, "every setting as a dict")
      .def_property_readonly("block_count", [](const PyScene& s) { return s.scene.blocks.size(); })
      .def_property_readonly("measure_points",
                             [](const PyScene& s) {
                               std::vector<std::string> names;
                               for (const MeasurePoint& p : s.scene.measure) names.push_back(p.name);
                               return names;
                             })
      .def("outlines",
           [](const PyScene& s) {
             py::list out;
             for (const BlockInput& b : s.scene.blocks) {
               py::array_t<double> a({static_cast<py::ssize_t>(b.polygon.size()), py::ssize_t{2}});
               auto w = a.mutable_unchecked<2>();
               for (size_t i = 0; i < b.polygon.size(); ++i) w(i, 0) = b.polygon[i].x(), w(i, 1) = b.polygon[i].y();
               out.append(a);
             }
             return out;
           },
           "the blocks at t = 0 as N x 2 arrays (x, y), in the scene's order")
      .def("fixed", [](const PyScene& s) {
        std::vector<bool> f;
        for (const BlockInput& b : s.scene.blocks) f.push_back(b.fixed);
        return f;
      });
}

}  // namespace ddafit::python
