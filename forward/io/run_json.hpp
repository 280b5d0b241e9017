// A run's results as JSON values: a measure point's quantities (kPointQuantities, flags
// as true/false) and the whole result as the text that crosses processes (an MPI
// worker's child to rank 0, a SLURM task's file to `scan --collect`). summary.json
// (run_files.hpp), the run codec and the evaluation cache all write points through here.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "forward/run_summary.hpp"

namespace ddafit::io {

// {"max_lateral_displacement": ..., ..., "stopped": false}: the quantities of one point,
// in table order (Json is nlohmann::json or nlohmann::ordered_json). The name is the
// caller's: a key of summary.json, a field of the cache.
template <class Json>
Json point_json(const PointSummary& p) {
  Json j = Json::object();
  for (const PointQuantity& q : kPointQuantities) j[q.name] = q.flag ? Json(q.get(p) != 0.0) : Json(q.get(p));
  return j;
}

// The inverse. JSON has no NaN: a non-finite value was written as null and reads back as
// NaN. Throws nlohmann's exceptions when a quantity is missing.
template <class Json>
void read_point_json(const Json& j, PointSummary& p) {
  for (const PointQuantity& q : kPointQuantities) {
    const Json& v = j.at(q.name);
    q.set(p, q.flag ? (v.template get<bool>() ? 1.0 : 0.0) : v.is_number() ? v.template get<double>() : NAN);
  }
}

// "completed", "invalid_scene", "failed", "interrupted".
const char* status_name(RunStatus status);

// The part of a result the objective reads (status, message, the points' summaries,
// simulated time) and the run's wall seconds, as one line of JSON, and back. decode_run
// throws nlohmann's exceptions on text that is not an encoded run.
std::string encode_run(const SimulationResult& run, double seconds);
SimulationResult decode_run(const std::string& text, double* seconds);

}  // namespace ddafit::io
