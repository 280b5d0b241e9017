#include "inverse/evaluation_cache.hpp"

#include <sqlite3.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "forward/io/run_json.hpp"

namespace ddafit::inverse {

std::string point_key(const Study& study, const std::vector<double>& values) {
  std::string key;
  for (size_t k = 0; k < values.size() && k < study.parameters.size(); ++k) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &values[k], sizeof bits);
    char hex[20];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(bits));
    key += (k ? ";" : "") + study.parameters[k].key + "=" + hex;
  }
  return key;
}

namespace {

// A prepared statement that finalizes itself.
struct Statement {
  sqlite3_stmt* s = nullptr;
  Statement(sqlite3* db, const char* sql, const std::string& path) {
    if (sqlite3_prepare_v2(db, sql, -1, &s, nullptr) != SQLITE_OK)
      throw CacheError(path + ": cache: " + sqlite3_errmsg(db));
  }
  ~Statement() { sqlite3_finalize(s); }
  void text(int i, const std::string& v) { sqlite3_bind_text(s, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT); }
  // Parameters ?1-?3: the row key (model version, scene hash, exact point).
  void key(const std::string& model_version, const std::string& scene_hash, const std::string& point) {
    text(1, model_version);
    text(2, scene_hash);
    text(3, point);
  }
};

constexpr int kHistoryColumns = 8;  // time, point, x, y, ux, uy, vx, vy

nlohmann::json summary_json(const SimulationSummary& s) {
  nlohmann::json points = nlohmann::json::array();
  for (const PointSummary& p : s.points) {
    nlohmann::json point = io::point_json<nlohmann::json>(p);
    point["name"] = p.name;
    points.push_back(point);
  }
  // The ground surface the run left (a deposit observation reads it), as [[x, y], ...].
  nlohmann::json surface = nlohmann::json::array();
  for (const Vec2& p : s.final_surface) surface.push_back({p.x(), p.y()});
  return {{"points", points}, {"warnings", s.warnings}, {"final_surface", surface}};
}

SimulationSummary summary_from_json(const nlohmann::json& j) {
  SimulationSummary s;
  for (const auto& p : j.at("points")) {
    PointSummary q;
    q.name = p.at("name").get<std::string>();
    io::read_point_json(p, q);
    s.points.push_back(q);
  }
  s.warnings = j.at("warnings").get<std::vector<std::string>>();
  if (j.contains("final_surface"))
    for (const auto& p : j["final_surface"]) s.final_surface.emplace_back(p.at(0).get<double>(), p.at(1).get<double>());
  return s;
}

}  // namespace

EvaluationCache::EvaluationCache(const std::string& path, std::string model_version, std::string scene_hash)
    : path_(path), model_version_(std::move(model_version)), scene_hash_(std::move(scene_hash)) {
  if (sqlite3_open(path.c_str(), &db_) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw CacheError(path + ": cannot open the evaluation cache: " + why);
  }
  sqlite3_busy_timeout(db_, 5000);
  // WAL + FULL: a row is on disk when its statement returns, and a torn write is rolled
  // back at the next open, so a kill -9 costs at most the forward run in flight.
  exec("PRAGMA journal_mode=WAL");
  exec("PRAGMA synchronous=FULL");
  exec("CREATE TABLE IF NOT EXISTS evaluations ("
       " model_version TEXT NOT NULL, scene_hash TEXT NOT NULL, point TEXT NOT NULL,"
       " status INTEGER NOT NULL, message TEXT NOT NULL, summary TEXT NOT NULL,"
       " wall_seconds REAL NOT NULL, history BLOB, created TEXT DEFAULT CURRENT_TIMESTAMP,"
       " PRIMARY KEY (model_version, scene_hash, point))");
}

EvaluationCache::~EvaluationCache() { sqlite3_close(db_); }

void EvaluationCache::exec(const char* sql) const {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string why = err ? err : "unknown error";
    sqlite3_free(err);
    throw CacheError(path_ + ": evaluation cache: " + why);
  }
}

std::optional<CachedRun> EvaluationCache::find(const std::string& key) const {
  Statement st(db_,
               "SELECT status, message, summary, wall_seconds, history FROM evaluations"
               " WHERE model_version = ?1 AND scene_hash = ?2 AND point = ?3",
               path_);
  st.key(model_version_, scene_hash_, key);
  const int rc = sqlite3_step(st.s);
  if (rc == SQLITE_DONE) return std::nullopt;
  if (rc != SQLITE_ROW) throw CacheError(path_ + ": evaluation cache: " + sqlite3_errmsg(db_));
  CachedRun run;
  try {
    run.result.summary = summary_from_json(
        nlohmann::json::parse(reinterpret_cast<const char*>(sqlite3_column_text(st.s, 2))));
  } catch (const std::exception&) {
    return std::nullopt;  // an unreadable row is treated as absent: the point is run again
  }
  run.result.summary.status = static_cast<RunStatus>(sqlite3_column_int(st.s, 0));
  run.result.summary.message = reinterpret_cast<const char*>(sqlite3_column_text(st.s, 1));
  run.wall_seconds = sqlite3_column_double(st.s, 3);
  if (sqlite3_column_type(st.s, 4) == SQLITE_BLOB) {
    const int bytes = sqlite3_column_bytes(st.s, 4);
    const auto* data = static_cast<const double*>(sqlite3_column_blob(st.s, 4));
    const int rows = bytes / static_cast<int>(sizeof(double) * kHistoryColumns);
    for (int r = 0; r < rows; ++r) {
      const double* v = data + r * kHistoryColumns;
      HistoryRow row;
      row.time = v[0];
      row.point = static_cast<int>(v[1]);
      row.position = Vec2(v[2], v[3]);
      row.displacement = Vec2(v[4], v[5]);
      row.velocity = Vec2(v[6], v[7]);
      run.result.history.push_back(row);
    }
    run.has_history = true;
  }
  return run;
}

void EvaluationCache::store(const std::string& key, const SimulationResult& run, double wall_seconds,
                            bool with_history) {
  Statement st(db_,
               "INSERT OR REPLACE INTO evaluations (model_version, scene_hash, point, status, message, summary,"
               " wall_seconds, history) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)",
               path_);
  st.key(model_version_, scene_hash_, key);
  sqlite3_bind_int(st.s, 4, static_cast<int>(run.summary.status));
  st.text(5, run.summary.message);
  st.text(6, summary_json(run.summary).dump());
  sqlite3_bind_double(st.s, 7, wall_seconds);
  std::vector<double> blob;
  if (with_history) {
    blob.reserve(run.history.size() * kHistoryColumns);
    for (const HistoryRow& r : run.history)
      blob.insert(blob.end(), {r.time, static_cast<double>(r.point), r.position.x(), r.position.y(),
                               r.displacement.x(), r.displacement.y(), r.velocity.x(), r.velocity.y()});
    sqlite3_bind_blob(st.s, 8, blob.data(), static_cast<int>(blob.size() * sizeof(double)), SQLITE_TRANSIENT);
  } else {
    sqlite3_bind_null(st.s, 8);
  }
  if (sqlite3_step(st.s) != SQLITE_DONE) throw CacheError(path_ + ": evaluation cache: " + sqlite3_errmsg(db_));
}

long EvaluationCache::count() const {
  Statement st(db_, "SELECT COUNT(*) FROM evaluations WHERE model_version = ?1 AND scene_hash = ?2", path_);
  st.text(1, model_version_);
  st.text(2, scene_hash_);
  return sqlite3_step(st.s) == SQLITE_ROW ? static_cast<long>(sqlite3_column_int64(st.s, 0)) : 0;
}

}  // namespace ddafit::inverse
