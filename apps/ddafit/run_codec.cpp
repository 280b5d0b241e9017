#include "apps/ddafit/run_codec.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

namespace ddafit::app {

std::string encode_run(const SimulationResult& r, double seconds) {
  nlohmann::json j;
  j["status"] = static_cast<int>(r.summary.status);
  j["message"] = r.summary.message;
  j["simulated_time"] = r.summary.run.simulated_time;
  j["seconds"] = seconds;
  j["points"] = nlohmann::json::array();
  // Each point as [name, quantities in kPointQuantities order].
  for (const PointSummary& p : r.summary.points) {
    nlohmann::json point = nlohmann::json::array({p.name});
    for (const PointQuantity& q : kPointQuantities)
      point.push_back(q.flag ? nlohmann::json(q.get(p) != 0.0) : nlohmann::json(q.get(p)));
    j["points"].push_back(point);
  }
  return j.dump();
}

SimulationResult decode_run(const std::string& text, double* seconds) {
  SimulationResult r;
  const nlohmann::json j = nlohmann::json::parse(text);
  r.summary.status = static_cast<RunStatus>(j["status"].get<int>());
  r.summary.message = j["message"].get<std::string>();
  r.summary.run.simulated_time = j["simulated_time"].is_number() ? j["simulated_time"].get<double>() : 0.0;
  *seconds = j["seconds"].is_number() ? j["seconds"].get<double>() : 0.0;
  // JSON has no NaN: a non-finite value was written as null and reads back as NaN.
  const auto number = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : NAN; };
  for (const auto& p : j["points"]) {
    PointSummary point;
    point.name = p[0].get<std::string>();
    int column = 1;
    for (const PointQuantity& q : kPointQuantities) {
      const nlohmann::json& v = p[column++];
      q.set(point, q.flag ? (v.get<bool>() ? 1.0 : 0.0) : number(v));
    }
    r.summary.points.push_back(point);
  }
  return r;
}

}  // namespace ddafit::app
