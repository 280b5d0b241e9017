// The inversion's one view of the forward model: the study's scene, read once, and the
// run at one point of its parameters. Parameters reach the scene as numbers through the
// key -> setter table of forward/io/scene_parameter.hpp. Nothing here throws except
// StudyScene::at(): a scene that cannot be read or a run that fails comes back as a
// SimulationResult with a status and a message.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "forward/io/scene_parameter.hpp"
#include "forward/simulation.hpp"
#include "inverse/study.hpp"

namespace ddafit::inverse {

// simulate(scene), with an exception turned into a failed run. Tests may substitute
// their own model.
using ForwardModel = std::function<SimulationResult(const Scene& scene)>;
SimulationResult run_forward(const Scene& scene);

// A value as text that reads back as the same double (17 digits): for files and messages.
std::string exact_text(double value);

// The study's scene, read once with the study's fixed settings, and each parameter's key
// resolved to its setter.
class StudyScene {
 public:
  // Never throws: a scene that cannot be read, or a parameter key it rejects, becomes the
  // problem every point then reports as an invalid scene (check_study_against_scene()
  // turns it into a StudyError before a study starts).
  explicit StudyScene(const Study& study);

  // The scene at one point (a value per study parameter). Throws io::SceneReadError.
  Scene at(const std::vector<double>& values) const;
  // forward(at(values)), as ensemble realisation `realisation` (forward/perturb.hpp; 0 =
  // the scene as given); a value the scene refuses is a run with status InvalidScene.
  SimulationResult run(const std::vector<double>& values, const ForwardModel& forward, int realisation = 0) const;
  // Peak friction angle (deg) of the interface a key "interfaces.NAME.*" belongs to, at
  // the given point; NaN when the key names no interface or the point is refused.
  double peak_friction_angle(const std::vector<double>& values, const std::string& key) const;

  // Empty when the scene was read and every key resolved; else the reader's one line, and
  // the parameter whose key it rejected (-1 when the scene itself is at fault).
  const std::string& problem() const { return problem_; }
  int rejected_parameter() const { return rejected_parameter_; }

 private:
  Scene base_;
  std::vector<io::SceneParameter> parameters_;
  // The parameter whose level `sled` runs the sled (study.hpp, kSledLevel), -1 if none, and
  // the block size its slices are cut at (the next level).
  int sled_parameter_ = -1;
  double sled_block_size_ = 0.0;
  std::string problem_;
  int rejected_parameter_ = -1;
};

// FNV-1a 64-bit hash, hex, of everything the scene reader reads for this study: the scene
// file, its `base:` chain, every file a scene names that exists next to it (CSV surfaces),
// and the study's fixed settings. Changing any of these starts a new cache key.
std::string scene_input_hash(const Study& study);

// The same hash of pieces of text (each piece ends with a separator): the key of a scene
// given whole, as `simulate --ensemble` caches its realisations under.
std::string text_hash(const std::vector<std::string>& pieces);

}  // namespace ddafit::inverse
