#include "inverse/forward_call.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "forward/io/scene_reader.hpp"

namespace ddafit::inverse {

namespace {

SimulationResult refused(RunStatus status, const std::string& message) {
  SimulationResult result;
  result.summary.status = status;
  result.summary.message = message;
  return result;
}

}  // namespace

SimulationResult run_forward(const Scene& scene) {
  try {
    return simulate(scene);
  } catch (const std::exception& e) {
    return refused(RunStatus::Failed, std::string("forward run threw: ") + e.what());
  } catch (...) {
    return refused(RunStatus::Failed, "forward run threw an unknown exception");
  }
}

std::string exact_text(double value) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return buf;
}

StudyScene::StudyScene(const Study& study) {
  try {
    // The fixed settings are the scene file's own text (any YAML value); read them once.
    base_ = io::read_scene(study.scene_path, study.settings);
  } catch (const io::SceneReadError& e) {
    problem_ = e.what();
    return;
  }
  for (size_t k = 0; k < study.parameters.size(); ++k) {
    const Parameter& p = study.parameters[k];
    if (p.sled_first && p.levels.size() > 1) {
      sled_parameter_ = static_cast<int>(k);
      sled_block_size_ = p.levels[1];
    }
    try {
      parameters_.emplace_back(base_, study.parameters[k].key, study.scene_path);
    } catch (const io::SceneReadError& e) {
      problem_ = e.what();
      rejected_parameter_ = static_cast<int>(k);
      parameters_.clear();
      return;
    }
  }
}

Scene StudyScene::at(const std::vector<double>& values) const {
  if (!problem_.empty()) throw io::SceneReadError(problem_);
  Scene scene = base_;
  const bool sled = sled_parameter_ >= 0 && values[sled_parameter_] == kSledLevel;
  if (!sled) {
    io::set_parameters(scene, parameters_, values);
    return scene;
  }
  std::vector<double> cut = values;
  cut[sled_parameter_] = sled_block_size_;
  io::set_parameters(scene, parameters_, cut);
  scene.options.integrator = Integrator::Sled;
  return scene;
}

SimulationResult StudyScene::run(const std::vector<double>& values, const ForwardModel& forward,
                                 int realisation) const {
  Scene scene;
  try {
    scene = at(values);
    scene.options.realisation = realisation;
  } catch (const io::SceneReadError& e) {
    return refused(RunStatus::InvalidScene, e.what());
  } catch (const std::exception& e) {
    return refused(RunStatus::Failed, std::string("setting the study's parameters threw: ") + e.what());
  }
  try {
    return forward(scene);
  } catch (const std::exception& e) {  // the forward model promises not to throw; be sure
    return refused(RunStatus::Failed, std::string("forward run threw: ") + e.what());
  }
}

double StudyScene::peak_friction_angle(const std::vector<double>& values, const std::string& key) const {
  if (key.rfind("interfaces.", 0) != 0) return std::numeric_limits<double>::quiet_NaN();
  const std::string rest = key.substr(11);
  const std::string name = rest.substr(0, rest.rfind('.'));
  try {
    for (const Interface& i : at(values).interfaces)
      if (i.name == name) return i.friction_angle;
  } catch (const std::exception&) {
  }
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {

struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void add(const std::string& s) {
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    h = (h ^ 0xff) * 1099511628211ull;  // separator, so "ab"+"c" differs from "a"+"bc"
  }
};

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Adds a scene file, its base chain and the files its scalars name (regions' CSV surfaces).
void add_scene_file(const std::filesystem::path& path, Fnv1a& hash, std::set<std::string>& seen, int depth) {
  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
  if (depth > 8 || !seen.insert(ec ? path.string() : canonical.string()).second) return;
  const std::string text = slurp(path);
  hash.add(path.filename().string());
  hash.add(text);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception&) {
    return;  // the reader will report it; the text is already in the hash
  }
  const std::filesystem::path dir = path.parent_path();
  std::vector<YAML::Node> stack{root};
  while (!stack.empty()) {
    const YAML::Node n = stack.back();
    stack.pop_back();
    if (n.IsScalar()) {
      const std::filesystem::path named = dir / n.Scalar();
      std::error_code named_ec;
      if (n.Scalar().size() < 256 && std::filesystem::is_regular_file(named, named_ec)) {
        const std::filesystem::path key = std::filesystem::weakly_canonical(named, named_ec);
        if (named.extension() == ".yaml" || named.extension() == ".yml")
          add_scene_file(named, hash, seen, depth + 1);
        else if (seen.insert(named_ec ? named.string() : key.string()).second)
          hash.add(n.Scalar()), hash.add(slurp(named));
      }
    } else if (n.IsSequence()) {
      for (const auto& item : n) stack.push_back(item);
    } else if (n.IsMap()) {
      for (const auto& kv : n) stack.push_back(kv.second);
    }
  }
}

}  // namespace

namespace {
std::string hex(const Fnv1a& hash) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash.h));
  return buf;
}
}  // namespace

std::string scene_input_hash(const Study& study) {
  Fnv1a hash;
  std::set<std::string> seen;
  add_scene_file(study.scene_path, hash, seen, 0);
  for (const auto& [key, value] : study.settings) hash.add(key + "=" + value);
  return hex(hash);
}

std::string text_hash(const std::vector<std::string>& pieces) {
  Fnv1a hash;
  for (const std::string& piece : pieces) hash.add(piece);
  return hex(hash);
}

void check_study_against_scene(const Study& study) {
  const StudyScene scene(study);
  if (scene.rejected_parameter() >= 0)
    throw StudyError(study.path + ": parameters[" + std::to_string(scene.rejected_parameter()) +
                     "].key: the scene rejects it: " + scene.problem());
  std::vector<double> start;
  for (const Parameter& p : study.parameters) start.push_back(p.discrete() ? p.levels.front() : p.start);
  for (size_t k = 0; k < study.parameters.size(); ++k) {
    if (!study.parameters[k].sled_first) continue;
    // The sled has no contact stress history: a thermal-pressurization interface cannot run on it.
    Scene probe;
    try {
      probe = scene.at(start);
    } catch (const io::SceneReadError&) {
      break;  // reported below with the entry that caused it
    }
    for (const Interface& f : probe.interfaces)
      if (f.law == FrictionLaw::ThermalPressurization)
        throw StudyError(study.path + ": parameters[" + std::to_string(k) + "].levels: sled cannot run interface '" +
                         f.name + "' (law thermal_pressurization needs the DDA solvers); start the levels with a block size");
  }
  Scene at_start;
  try {
    at_start = scene.at(start);
  } catch (const io::SceneReadError& e) {
    // Name the study entry whose value the scene refused, when there is one.
    const std::string what = e.what();
    for (size_t k = 0; k < study.parameters.size(); ++k)
      if (what.find(study.parameters[k].key) != std::string::npos)
        throw StudyError(study.path + ": parameters[" + std::to_string(k) + "].key: the scene rejects it: " + what);
    throw StudyError(study.path + ": scene: " + what);
  }
  for (size_t k = 0; k < study.observations.size(); ++k) {
    if (study.observations[k].is_deposit()) continue;  // the whole surface, no point
    const std::string& point = study.observations[k].point;
    std::string names;
    bool found = false;
    for (const MeasurePoint& m : at_start.measure) {
      found = found || m.name == point;
      names += (names.empty() ? "" : ", ") + m.name;
    }
    if (!found)
      throw StudyError(study.path + ": observations[" + std::to_string(k) + "].point: unknown point '" + point +
                       "'; the scene measures: " + (names.empty() ? "none" : names));
  }
}

}  // namespace ddafit::inverse
