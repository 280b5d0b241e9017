#include "forward/io/run_json.hpp"

namespace ddafit::io {

const char* status_name(RunStatus s) {
  switch (s) {
    case RunStatus::Completed: return "completed";
    case RunStatus::InvalidScene: return "invalid_scene";
    case RunStatus::Failed: return "failed";
    case RunStatus::Interrupted: return "interrupted";
  }
  return "unknown";
}

std::string encode_run(const SimulationResult& r, double seconds) {
  nlohmann::json j;
  j["status"] = static_cast<int>(r.summary.status);
  j["message"] = r.summary.message;
  j["simulated_time"] = r.summary.run.simulated_time;
  j["seconds"] = seconds;
  j["final_surface"] = nlohmann::json::array();
  for (const Vec2& p : r.summary.final_surface) j["final_surface"].push_back({p.x(), p.y()});
  j["points"] = nlohmann::json::array();
  for (const PointSummary& p : r.summary.points) {
    nlohmann::json point = point_json<nlohmann::json>(p);
    point["name"] = p.name;
    j["points"].push_back(point);
  }
  return j.dump();
}

SimulationResult decode_run(const std::string& text, double* seconds) {
  SimulationResult r;
  const nlohmann::json j = nlohmann::json::parse(text);
  r.summary.status = static_cast<RunStatus>(j.at("status").get<int>());
  r.summary.message = j.at("message").get<std::string>();
  r.summary.run.simulated_time = j["simulated_time"].is_number() ? j["simulated_time"].get<double>() : 0.0;
  *seconds = j["seconds"].is_number() ? j["seconds"].get<double>() : 0.0;
  if (j.contains("final_surface"))
    for (const auto& p : j["final_surface"]) r.summary.final_surface.emplace_back(p.at(0).get<double>(), p.at(1).get<double>());
  for (const auto& p : j.at("points")) {
    PointSummary point;
    point.name = p.at("name").get<std::string>();
    read_point_json(p, point);
    r.summary.points.push_back(point);
  }
  return r;
}

}  // namespace ddafit::io
