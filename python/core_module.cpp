// ddafit._core: the forward model, the stable search and the back-analysis for Python
// (python/ddafit/__init__.py is the module users import). Values cross as Python types:
// a summary is the dict of summary.json, a history NumPy arrays per measure point, block
// outlines N x 2 arrays. A scene or study that cannot be used raises ValueError with the
// one line the command line prints; long calls release the GIL and stop on Ctrl-C
// (the run's status is then "interrupted", and the package raises ddafit.Interrupted).
#include <algorithm>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "batch/stop_signals.hpp"
#include "batch/thread_budget.hpp"
#include "forward/analysis/stable_friction.hpp"
#include "forward/io/run_files.hpp"
#include "forward/io/scene_reader.hpp"
#include "forward/model_revision.hpp"
#include "forward/mirror.hpp"
#include "forward/simulation.hpp"
#include "inverse/hypotheses.hpp"
#include "inverse/inversion.hpp"
#include "inverse/report.hpp"
#include "inverse/study.hpp"
#include "python/scene_settings.hpp"

namespace py = pybind11;

namespace ddafit::python {
namespace {

py::object json_loads(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

io::Overrides overrides_of(const py::dict& settings) {
  io::Overrides out;
  for (const auto& [key, value] : settings) out.emplace_back(py::str(key).cast<std::string>(), setting_text(value));
  return out;
}

py::array_t<double> outline_array(const std::vector<Vec2>& polygon) {
  py::array_t<double> a({static_cast<py::ssize_t>(polygon.size()), py::ssize_t{2}});
  auto w = a.mutable_unchecked<2>();
  for (size_t i = 0; i < polygon.size(); ++i) w(i, 0) = polygon[i].x(), w(i, 1) = polygon[i].y();
  return a;
}

PyScene load(const std::string& path, const py::dict& settings) {
  PyScene s;
  s.path = path;
  s.overrides = overrides_of(settings);
  s.scene = io::read_scene(path, s.overrides);
  return s;
}

PyScene scene_from(const py::object& scene_or_path, const py::dict& settings) {
  if (py::isinstance<PyScene>(scene_or_path)) {
    PyScene s = scene_or_path.cast<PyScene>();
    if (py::len(settings) > 0) {
      for (const auto& kv : overrides_of(settings)) s.overrides.push_back(kv);
      s.scene = io::read_scene(s.path, s.overrides);
    }
    return s;
  }
  return load(py::str(scene_or_path).cast<std::string>(), settings);
}

// Asks Python, at most every 0.1 s of wall, whether Ctrl-C was pressed; the run then stops
// with status Interrupted and keeps its history so far.
struct InterruptCheck {
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
  bool interrupted = false;
  bool operator()() {
    const auto now = std::chrono::steady_clock::now();
    if (interrupted) return true;
    if (now - last < std::chrono::milliseconds(100)) return false;
    last = now;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) {
      PyErr_Clear();  // the package raises ddafit.Interrupted with the result instead
      interrupted = true;
    }
    return interrupted;
  }
};

struct PyResult {
  py::dict summary;
  py::dict history;
  py::list blocks;  // outlines at the last output
  py::list fixed;   // per block
};

PyResult simulate_scene(const py::object& scene_or_path, int threads, const py::dict& settings, bool mirror) {
  const PyScene s = scene_from(scene_or_path, settings);
  // --mirror of the command line (forward/mirror.hpp): the mirror image run, read back.
  const Scene run_scene = mirror ? mirrored_scene(s.scene) : s.scene;
  batch::set_thread_budget(threads);  // 0: one per core; BLAS held to one (thread_budget.hpp)
  std::vector<std::vector<Vec2>> outlines;
  std::vector<bool> fixed;
  SimulationResult result;
  {
    InterruptCheck check;
    SimulationHooks hooks;
    hooks.on_output = [&](double, const BlockSystem& system) {
      outlines.clear();
      fixed.clear();
      for (const Block& b : system.blocks) {
        outlines.emplace_back(system.vertices.begin() + b.first_vertex,
                              system.vertices.begin() + b.first_vertex + b.vertex_count);
        if (mirror) {  // reflected back, corners in the scene's order again
          for (Vec2& v : outlines.back()) v.x() = -v.x();
          std::reverse(outlines.back().begin(), outlines.back().end());
        }
        fixed.push_back(b.fixed);
      }
    };
    hooks.should_stop = [&] { return check(); };
    py::gil_scoped_release release;
    result = simulate(run_scene, hooks);
  }
  if (mirror) unmirror_history(result.history);
  if (result.summary.status == RunStatus::InvalidScene) throw py::value_error(s.path + ": " + result.summary.message);
  PyResult r;
  r.summary = json_loads(io::summary_json_text(s.path, result));
  // The history rows, point by point, as arrays.
  std::map<int, std::vector<const HistoryRow*>> rows;
  for (const HistoryRow& row : result.history) rows[row.point].push_back(&row);
  for (const auto& [point, list] : rows) {
    const auto column = [&](auto get) {
      py::array_t<double> a(static_cast<py::ssize_t>(list.size()));
      auto w = a.mutable_unchecked<1>();
      for (size_t i = 0; i < list.size(); ++i) w(i) = get(*list[i]);
      return a;
    };
    py::dict d;
    d["time"] = column([](const HistoryRow& h) { return h.time; });
    d["x"] = column([](const HistoryRow& h) { return h.position.x(); });
    d["y"] = column([](const HistoryRow& h) { return h.position.y(); });
    d["ux"] = column([](const HistoryRow& h) { return h.displacement.x(); });
    d["uy"] = column([](const HistoryRow& h) { return h.displacement.y(); });
    d["vx"] = column([](const HistoryRow& h) { return h.velocity.x(); });
    d["vy"] = column([](const HistoryRow& h) { return h.velocity.y(); });
    r.history[py::str(s.scene.measure[point].name)] = d;
  }
  for (size_t b = 0; b < outlines.size(); ++b) {
    r.blocks.append(outline_array(outlines[b]));
    r.fixed.append(py::bool_(fixed[b]));
  }
  return r;
}

py::object stable_search(const py::object& scene_or_path, const std::string& interface, double low, double high,
                         double tolerance, double trial, double rest_window, double movement, const py::dict& settings) {
  const PyScene s = scene_from(scene_or_path, settings);
  StableSearchOptions o;
  for (size_t k = 0; k < s.scene.interfaces.size(); ++k)
    if (s.scene.interfaces[k].name == interface) o.interface = static_cast<int>(k);
  if (o.interface < 0) throw py::value_error(s.path + ": interface: no interface '" + interface + "' in the scene");
  o.low = low, o.high = high, o.tolerance = tolerance, o.trial_duration = trial, o.rest_window = rest_window;
  o.max_movement = movement;
  if (!(o.low < o.high) || !(o.tolerance > 0.0) || !(o.trial_duration > 0.0) || !(o.max_movement >= 0.0))
    throw py::value_error("stable: need low < high and positive tolerance, trial and movement");
  StableSearchResult r;
  {
    py::gil_scoped_release release;
    r = find_stable_friction(s.scene, o, [](const StableTrial&) {});
  }
  return json_loads(io::stable_json_text({s.path, interface, s.scene.rest_speed, o}, r));
}

py::object invert_study(const std::string& study_path, const std::string& out, bool resume, int budget) {
  const inverse::Study study = inverse::read_checked_study(study_path);
  if (!study.hypotheses.empty()) throw py::value_error(study_path + ": hypotheses: rank them with the command line, ddafit invert");
  inverse::InversionOptions options;
  options.out_dir = out;
  options.resume = resume;
  options.budget = budget;
  options.model_version = std::string(DDAFIT_VERSION) + "+" + kModelRevision;
  inverse::InversionSummary summary;
  {
    py::gil_scoped_release release;
    summary = inverse::run_inversion(study, options);
    inverse::write_report(out, study, summary);
  }
  std::ifstream in(std::filesystem::path(out) / "report.json");
  std::stringstream text;
  text << in.rdbuf();
  return json_loads(text.str());
}

}  // namespace
}  // namespace ddafit::python

PYBIND11_MODULE(_core, m) {
  using namespace ddafit;
  using namespace ddafit::python;
  m.doc() = "ddafit: DDA back-analysis of rapid landslides (see docs/python.md)";
  m.attr("model_revision") = kModelRevision;
  m.attr("version") = DDAFIT_VERSION;
  // Input that cannot be used: ValueError with the command line's one-line message.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::SceneReadError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const inverse::StudyError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const inverse::InversionError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  bind_scene(m);
  py::class_<PyResult>(m, "Result", "A forward run: summary (summary.json), history and the last output's blocks")
      .def_readonly("summary", &PyResult::summary)
      .def_readonly("history", &PyResult::history)
      .def_readonly("blocks", &PyResult::blocks)
      .def_readonly("fixed", &PyResult::fixed);
  m.def("load_scene", &load, py::arg("path"), py::arg("settings") = py::dict());
  m.def("simulate", &simulate_scene, py::arg("scene"), py::arg("threads") = 0, py::arg("settings") = py::dict(),
        py::arg("mirror") = false);
  m.def("stable", &stable_search, py::arg("scene"), py::arg("interface"), py::arg("low") = 5.0, py::arg("high") = 45.0,
        py::arg("tolerance") = 0.5, py::arg("trial") = 10.0, py::arg("rest_window") = 1.0, py::arg("movement") = 0.0,
        py::arg("settings") = py::dict());
  m.def("invert", &invert_study, py::arg("study"), py::arg("out"), py::arg("resume") = false, py::arg("budget") = 0);
}
