// Reads study files (format: study.hpp, docs/back-analysis.md). Every failure is one line,
// "FILE: KEY: PROBLEM", using the scene reader's checked YAML access.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "forward/io/yaml_checks.hpp"
#include "forward/run_summary.hpp"
#include "inverse/study.hpp"

#include "forward/io/region_reader.hpp"
#include "forward/io/text_input.hpp"

namespace ddafit::inverse {

const std::vector<std::string>& summary_quantities() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const PointQuantity& q : kPointQuantities) all.emplace_back(q.name);
    return all;
  }();
  return names;
}

namespace {

using io::indexed;
using io::join;

class StudyReader : public io::YamlChecks {
 public:
  using YamlChecks::YamlChecks;

  Study read(const YAML::Node& root, const std::string& dir) const {
    dir_ = dir;
    if (!root.IsMap()) fail("(top level)", "expected a map with scene, parameters, observations");
    check_keys(root, "", {"scene", "settings", "parameters", "observations", "method", "profile", "ensemble",
                          "hypotheses"});
    Study s;
    s.path = file();
    const std::string scene = text(required(root, "", "scene", "name the scene file (relative to the study)"), "scene");
    const std::filesystem::path p(scene);
    s.scene_path = p.is_relative() && !dir.empty() ? (std::filesystem::path(dir) / p).string() : scene;
    std::error_code ec;  // a name too long for the file system is an error code, not an abort
    if (!std::filesystem::is_regular_file(s.scene_path, ec))
      fail("scene", "cannot find the file '" + io::printable(s.scene_path) + "'" + (ec ? " (" + ec.message() + ")" : ""));
    if (const YAML::Node n = root["settings"]) s.settings = settings(n, "settings");
    if (const YAML::Node n = root["hypotheses"]) s.hypotheses = hypotheses(n);
    // With hypotheses that all bring their own parameters, the study needs none.
    const bool own = !s.hypotheses.empty() && std::all_of(s.hypotheses.begin(), s.hypotheses.end(),
                                                          [](const Hypothesis& h) { return !h.parameters.empty(); });
    if (const YAML::Node params = own ? root["parameters"] : required(root, "", "parameters", "list the scene values to fit")) {
      s.parameters = parameter_list(params, "parameters");
    } else {
      s.parameters = s.hypotheses.front().parameters;  // the profile's and reports' default
    }
    const YAML::Node obs = required(root, "", "observations", "list what was observed");
    list(obs, "observations");
    if (obs.size() == 0) fail("observations", "the list is empty; give at least one observation");
    for (size_t k = 0; k < obs.size(); ++k) s.observations.push_back(observation(obs[k], indexed("observations", k)));
    if (const YAML::Node n = root["method"]) s.method = method(n);
    if (s.method.coarse_to_fine &&
        std::count_if(s.parameters.begin(), s.parameters.end(), [](const Parameter& q) { return q.discrete(); }) != 1)
      fail("method.levels", "coarse_to_fine needs exactly one parameter with levels (coarse first, e.g. block sizes)");
    if (const YAML::Node n = root["profile"]) s.profile = profile(n, s.parameters);
    if (s.method.multi_fidelity) {
      const auto& ps = s.parameters;
      const auto leveled = std::count_if(ps.begin(), ps.end(), [](const Parameter& q) { return q.discrete(); });
      const auto two = std::count_if(ps.begin(), ps.end(), [](const Parameter& q) { return q.levels.size() == 2; });
      if (leveled != 1 || two != 1)
        fail("method.levels", "multi_fidelity needs exactly one parameter with two levels (coarse, fine; e.g. block sizes)");
      if (profile_parameter(s) < 0)
        fail("method.levels", "multi_fidelity corrects the profile: give a *.degradation_percent or *.roughness_angle parameter");
      if (s.profile.points < 2) fail("profile.points", "multi_fidelity needs a profile of at least 2 points");
      if (s.profile.reoptimize) fail("profile.reoptimize", "not with levels: multi_fidelity (the correction is along one parameter)");
    }
    if (const YAML::Node n = root["ensemble"]) {
      const double k = number(n, "ensemble");
      if (!(k >= 2 && k <= 1000 && k == std::floor(k)))
        fail("ensemble", "is " + fmt(k) + "; give a whole number of realisations in [2, 1000]");
      s.ensemble = static_cast<int>(k);
    }
    return s;
  }

 private:
  mutable std::string dir_;  // the study file's folder: relative paths start there
  // Study numbers stay within +-1e12 and sigmas above 1e-12, so that a residual squared
  // (|value| / sigma)^2 <= 4e48 stays far from overflow: 1e308 or a denormal sigma once
  // took the Ceres fit to an error and the run to a segfault.
  static constexpr double kLargest = 1e12, kSmallest = 1e-12;
  double bounded(const YAML::Node& n, const std::string& path) const {
    const double v = number(n, path);
    if (!(std::abs(v) <= kLargest)) fail(path, "is " + fmt(v) + "; must be within +-1e12");
    return v;
  }
  double bounded(const YAML::Node& map, const std::string& path, const char* key, const char* hint) const {
    return bounded(required(map, path, key, hint), join(path, key));
  }

  std::vector<std::pair<std::string, std::string>> settings(const YAML::Node& n, const std::string& path) const {
    std::vector<std::pair<std::string, std::string>> out;
    for (const std::string& key : map_keys(n, path)) out.emplace_back(key, YAML::Dump(n[key]));
    return out;
  }

  std::vector<Parameter> parameter_list(const YAML::Node& n, const std::string& path) const {
    list(n, path);
    std::vector<Parameter> out;
    for (size_t k = 0; k < n.size(); ++k) out.push_back(parameter(n[k], indexed(path, k)));
    check_parameters(out, path);
    return out;
  }

  // hypotheses: [{name, settings: {KEY: VALUE}, parameters: [...]}, ...], at least two.
  std::vector<Hypothesis> hypotheses(const YAML::Node& n) const {
    list(n, "hypotheses");
    if (n.size() < 2) fail("hypotheses", "give at least two to rank (or leave the key out for one fit)");
    std::vector<Hypothesis> out;
    std::set<std::string> names;
    for (size_t k = 0; k < n.size(); ++k) {
      const std::string path = indexed("hypotheses", k);
      check_keys(n[k], path, {"name", "settings", "parameters"});
      Hypothesis h;
      h.name = text(required(n[k], path, "name", "give the hypothesis a name"), join(path, "name"));
      if (h.name.empty() || h.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
                                std::string::npos)
        fail(join(path, "name"), "'" + io::printable(h.name) + "' must be letters, digits, _ or - (it names a folder)");
      if (!names.insert(h.name).second) fail(join(path, "name"), "'" + h.name + "' is used twice");
      if (const YAML::Node s = n[k]["settings"]) h.settings = settings(s, join(path, "settings"));
      if (const YAML::Node p = n[k]["parameters"]) h.parameters = parameter_list(p, join(path, "parameters"));
      out.push_back(std::move(h));
    }
    return out;
  }

  Parameter parameter(const YAML::Node& n, const std::string& path) const {
    Parameter q;
    q.name = text(required(n, path, "name", "give the parameter a name"), join(path, "name"));
    q.key = text(required(n, path, "key", "name the scene value it sets, e.g. interfaces.clay.degradation_percent"),
                 join(path, "key"));
    if (const YAML::Node levels = n["levels"]) {
      check_keys(n, path, {"name", "key", "levels"});
      list(levels, join(path, "levels"));
      if (levels.size() == 0) fail(join(path, "levels"), "the list is empty; give at least one level");
      std::set<double> seen;
      for (size_t k = 0; k < levels.size(); ++k) {
        if (levels[k].IsScalar() && levels[k].Scalar() == "sled") {
          // Fidelity 0 first: the sled needs a cut at the next (numeric) block size.
          if (q.key != "mesh.block_size" || k != 0 || levels.size() < 2)
            fail(indexed(join(path, "levels"), k), "sled is the first level of a mesh.block_size parameter, followed "
                                                   "by block sizes (e.g. [sled, 34.3, 8.2])");
          q.levels.push_back(kSledLevel);
          q.sled_first = true;
          seen.insert(kSledLevel);
          continue;
        }
        q.levels.push_back(bounded(levels[k], indexed(join(path, "levels"), k)));
        if (!seen.insert(q.levels.back()).second) fail(indexed(join(path, "levels"), k), "repeats a level");
      }
      return q;
    }
    check_keys(n, path, {"name", "key", "lower", "upper", "start", "resolution", "levels"});
    q.lower = bounded(n, path, "lower", "give the lower bound");
    q.upper = bounded(n, path, "upper", "give the upper bound");
    q.start = bounded(n, path, "start", "give the first guess");
    q.resolution = bounded(n, path, "resolution", "give the smallest change that matters");
    if (!(q.lower < q.upper))
      fail(join(path, "upper"), "is " + fmt(q.upper) + ", not above lower " + fmt(q.lower) + "; the bounds are impossible");
    if (q.start < q.lower || q.start > q.upper)
      fail(join(path, "start"), "is " + fmt(q.start) + ", outside [" + fmt(q.lower) + ", " + fmt(q.upper) + "]");
    if (!(q.resolution > 0.0)) fail(join(path, "resolution"), "is " + fmt(q.resolution) + "; must be > 0");
    if (q.resolution >= q.upper - q.lower)
      fail(join(path, "resolution"), "is not smaller than upper - lower; nothing left to search");
    // Finite differences of the forward model at a relative 1e-9 of the range are round-off.
    if (q.resolution < 1e-9 * (q.upper - q.lower))
      fail(join(path, "resolution"), "is " + fmt(q.resolution) + ", below 1e-9 x (upper - lower); no change that small matters");
    return q;
  }

  void check_parameters(const std::vector<Parameter>& ps, const std::string& path) const {
    if (ps.empty()) fail(path, "the list is empty; give at least one parameter");
    std::set<std::string> names, keys;
    bool continuous = false;
    for (size_t k = 0; k < ps.size(); ++k) {
      if (!names.insert(ps[k].name).second) fail(indexed(path, k) + ".name", "'" + ps[k].name + "' is used twice");
      if (!keys.insert(ps[k].key).second) fail(indexed(path, k) + ".key", "'" + ps[k].key + "' is set twice");
      continuous = continuous || !ps[k].discrete();
    }
    // Both forms of one interface's roughness would overwrite each other in every run.
    for (size_t k = 0; k < ps.size(); ++k)
      if (const std::string tail = ".roughness_angle";
          ps[k].key.size() > tail.size() && ps[k].key.compare(ps[k].key.size() - tail.size(), tail.size(), tail) == 0) {
        const std::string stem = ps[k].key.substr(0, ps[k].key.size() - tail.size() + 1);
        if (keys.count(stem + "degradation_percent"))
          fail(indexed(path, k) + ".key", "'" + ps[k].key + "' and '" + stem +
                   "degradation_percent' are two forms of one roughness; make one of them the parameter");
      }
    if (!continuous) fail(path, "all are discrete levels; give at least one with lower, upper, start, resolution");
  }

  Observation observation(const YAML::Node& n, const std::string& path) const {
    check_keys(n, path, {"point", "quantity", "value", "sigma", "kind", "model_sigma", "surface", "from", "to"});
    Observation o;
    o.quantity = text(required(n, path, "quantity", "name a summary field"), join(path, "quantity"));
    if (o.is_deposit()) {
      // The deposit: a surveyed ground surface after the slide, compared over [from, to].
      if (n["point"]) fail(join(path, "point"), "deposit_rms compares the whole surface; it has no point");
      const std::string file = text(required(n, path, "surface", "name a CSV of the ground after (x_m,z_m)"),
                                    join(path, "surface"));
      o.surface = io::read_polyline_csv(*this, io::resolve_input_path(dir_, file), join(path, "surface"));
      o.from = bounded(n, path, "from", "give the deposit's first x, m");
      o.to = bounded(n, path, "to", "give the deposit's last x, m");
      if (!(o.from < o.to)) fail(join(path, "to"), "is " + fmt(o.to) + ", not above from " + fmt(o.from));
    } else {
      for (const char* key : {"surface", "from", "to"})
        if (n[key]) fail(join(path, key), "only for quantity: deposit_rms");
      o.point = text(required(n, path, "point", "name the scene's measure point"), join(path, "point"));
    }
    const auto& qs = summary_quantities();
    if (!o.is_deposit() && std::find(qs.begin(), qs.end(), o.quantity) == qs.end()) {
      std::string all;
      for (const std::string& q : qs) all += (all.empty() ? "" : ", ") + q;
      fail(join(path, "quantity"), "unknown quantity '" + o.quantity + "'; known: " + all);
    }
    o.value = bounded(n, path, "value", "give the observed value");
    o.sigma = bounded(n, path, "sigma", "give the observation's standard deviation");
    if (!(o.sigma >= kSmallest)) fail(join(path, "sigma"), "is " + fmt(o.sigma) + "; must be >= 1e-12");
    if (const YAML::Node m = n["model_sigma"]) {
      if (m.IsScalar() && m.Scalar() == "ensemble") {
        o.model_sigma_from_ensemble = true;
      } else {
        o.model_sigma = bounded(m, join(path, "model_sigma"));
        if (!(o.model_sigma >= 0.0))
          fail(join(path, "model_sigma"), "is " + fmt(o.model_sigma) + "; give a value >= 0 or 'ensemble'");
      }
    }
    if (const YAML::Node k = n["kind"]) {
      const std::string kind = text(k, join(path, "kind"));
      if (kind == "equal") o.kind = ObservationKind::Equal;
      else if (kind == "at_most") o.kind = ObservationKind::AtMost;
      else if (kind == "at_least") o.kind = ObservationKind::AtLeast;
      else fail(join(path, "kind"), "unknown kind '" + kind + "'; known: equal, at_most, at_least");
    }
    return o;
  }

  MethodOptions method(const YAML::Node& n) const {
    check_keys(n, "method",
               {"optimizer", "algorithm", "budget", "step_tolerance", "chi2_tolerance", "levels", "fine_budget",
                "fine_runs"});
    MethodOptions m;
    if (const YAML::Node o = n["optimizer"]) {
      const std::string name = text(o, "method.optimizer");
      if (name == "nlopt") m.optimizer = Optimizer::Nlopt;
      else if (name == "ceres") m.optimizer = Optimizer::Ceres;
      else fail("method.optimizer", "unknown optimizer '" + name + "'; known: nlopt, ceres");
    }
    if (const YAML::Node a = n["algorithm"]) {
      m.algorithm = text(a, "method.algorithm");
      if (m.optimizer != Optimizer::Nlopt) fail("method.algorithm", "only for optimizer: nlopt");
      if (m.algorithm != "LN_BOBYQA" && m.algorithm != "LN_SBPLX" && m.algorithm != "GN_DIRECT_L")
        fail("method.algorithm", "unknown algorithm '" + m.algorithm + "'; known: LN_BOBYQA, LN_SBPLX, GN_DIRECT_L");
    }
    // A number of forward runs: whole, at least 1.
    const auto runs = [&](const YAML::Node& b, const std::string& key) {
      const double value = number(b, key);
      if (!(value >= 1.0) || value != std::floor(value) || value > 1e6)
        fail(key, "is " + b.Scalar() + "; must be a whole number of forward runs >= 1");
      return static_cast<int>(value);
    };
    if (const YAML::Node b = n["budget"]) {
      m.budget = runs(b, "method.budget");
    }
    opt_number(n, "method", "step_tolerance", m.step_tolerance);
    opt_number(n, "method", "chi2_tolerance", m.chi2_tolerance);
    if (!(m.step_tolerance > 0.0)) fail("method.step_tolerance", "must be > 0 (a fraction of each resolution)");
    if (!(m.chi2_tolerance > 0.0)) fail("method.chi2_tolerance", "must be > 0");
    if (const YAML::Node l = n["levels"]) {
      const std::string how = text(l, "method.levels");
      if (how == "coarse_to_fine") m.coarse_to_fine = true;
      else if (how == "multi_fidelity") m.multi_fidelity = true;
      else if (how != "independent")
        fail("method.levels", "unknown strategy '" + how + "'; known: independent, coarse_to_fine, multi_fidelity");
    }
    if (const YAML::Node b = n["fine_budget"]) {
      if (!m.coarse_to_fine) fail("method.fine_budget", "only with levels: coarse_to_fine");
      m.fine_budget = runs(b, "method.fine_budget");
    }
    if (const YAML::Node b = n["fine_runs"]) {
      if (!m.multi_fidelity) fail("method.fine_runs", "only with levels: multi_fidelity");
      m.fine_runs = runs(b, "method.fine_runs");
      if (m.fine_runs < 2) fail("method.fine_runs", "is " + b.Scalar() + "; multi_fidelity needs at least 2 (a correction a + b p)");
    }
    return m;
  }

  ProfileOptions profile(const YAML::Node& n, const std::vector<Parameter>& ps) const {
    check_keys(n, "profile", {"parameter", "points", "reoptimize"});
    ProfileOptions p;
    if (const YAML::Node q = n["parameter"]) {
      p.parameter = text(q, "profile.parameter");
      const auto it = std::find_if(ps.begin(), ps.end(), [&](const Parameter& x) { return x.name == p.parameter; });
      if (it == ps.end()) fail("profile.parameter", "unknown parameter '" + p.parameter + "'");
      if (it->discrete()) fail("profile.parameter", "'" + p.parameter + "' has levels; profile a continuous parameter");
    }
    if (const YAML::Node q = n["points"]) {
      const double points = number(q, "profile.points");
      if (!(points >= 0.0) || points != std::floor(points) || points == 1.0 || points > 10000)
        fail("profile.points", "is " + q.Scalar() + "; must be 0 (no profile) or a whole number >= 2");
      p.points = static_cast<int>(points);
    }
    if (const YAML::Node q = n["reoptimize"]) p.reoptimize = scalar<bool>(q, "profile.reoptimize", "true or false");
    return p;
  }

  static std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }
};

}  // namespace

Study read_study(const std::string& path) {
  std::string problem;
  const std::string text = io::read_input_file(path, problem);
  if (!problem.empty()) throw StudyError(problem);
  try {
    if (io::yaml_document_count(text) > 1)
      throw StudyError(path + ": (top level): the file holds more than one YAML document (a '---' line starts "
                       "another, and everything after it would be ignored); keep one");
    const YAML::Node root = YAML::Load(text);
    return StudyReader(path).read(root, std::filesystem::path(path).parent_path().string());
  } catch (const io::SceneReadError& e) {
    throw StudyError(e.what());
  } catch (const YAML::Exception& e) {
    throw StudyError(path + ": line " + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
}

int profile_parameter(const Study& study) {
  const auto& ps = study.parameters;
  for (size_t k = 0; k < ps.size(); ++k)
    if (!study.profile.parameter.empty() && ps[k].name == study.profile.parameter) return static_cast<int>(k);
  if (!study.profile.parameter.empty()) return -1;
  const auto ends_with = [](const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
  };
  for (const char* tail : {".degradation_percent", ".roughness_angle"})
    for (size_t k = 0; k < ps.size(); ++k)
      if (!ps[k].discrete() && ps[k].key.rfind("interfaces.", 0) == 0 && ends_with(ps[k].key, tail))
        return static_cast<int>(k);
  return -1;
}

}  // namespace ddafit::inverse
