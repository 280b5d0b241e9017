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
  for (const PointSummary& p : r.summary.points)
    j["points"].push_back({p.name, p.max_lateral_displacement, p.max_total_displacement, p.peak_lateral_velocity,
                           p.peak_total_velocity, p.duration, p.stopped});
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
  for (const auto& p : j["points"])
    r.summary.points.push_back({p[0].get<std::string>(), number(p[1]), number(p[2]), number(p[3]), number(p[4]),
                                number(p[5]), p[6].get<bool>()});
  return r;
}

}  // namespace ddafit::app
