// Every forward run of a study, kept in an SQLite file so that a crash, a kill -9 or a
// deliberate stop loses at most the run in flight. One row per run, committed on its own
// (WAL journal, synchronous=FULL) before the optimiser sees the value.
//
// A row is keyed by (model version, scene input hash, point), where the point lists each
// parameter's scene key with the exact bits of its value, so a cached summary is only
// reused for the very same forward run. Misfits are not stored: they are recomputed from
// the stored summaries, so observations and sigmas may change between resumes.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "forward/simulation.hpp"
#include "inverse/study.hpp"

struct sqlite3;

namespace ddafit::inverse {

// The cache file cannot be opened or written. what() is one line naming the file.
struct CacheError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CachedRun {
  SimulationResult result;   // summary always; history only when it was stored
  double wall_seconds = 0.0;  // of the original run
  bool has_history = false;
};

// "key=HEX;key=HEX" with HEX the 64 bits of each double: equal text <=> identical point.
std::string point_key(const Study& study, const std::vector<double>& values);

class EvaluationCache {
 public:
  EvaluationCache(const std::string& path, std::string model_version, std::string scene_hash);
  ~EvaluationCache();
  EvaluationCache(const EvaluationCache&) = delete;
  EvaluationCache& operator=(const EvaluationCache&) = delete;

  std::optional<CachedRun> find(const std::string& key) const;
  // Stores one run, with its history when with_history (kept for best points only, to keep
  // the file small). Committed when this returns.
  void store(const std::string& key, const SimulationResult& run, double wall_seconds, bool with_history);
  // Rows for this model version and scene.
  long count() const;
  const std::string& path() const { return path_; }

 private:
  void exec(const char* sql) const;
  sqlite3* db_ = nullptr;
  std::string path_, model_version_, scene_hash_;
};

}  // namespace ddafit::inverse
