// The one way ddafit draws a chart: gnuplot on a script written beside the data (a
// runtime tool; when it is missing the charts are skipped with a note and the data files
// stay, so a user can draw them with their own tools).
#pragma once

#include <string>

namespace ddafit::io {

// Runs `gnuplot SCRIPT` with its errors in SCRIPT.log. Returns false with `reason` when
// gnuplot is not installed or fails; `kept` names what the caller wrote anyway, for the
// reason ("the data files", "report.md and report.json").
bool run_gnuplot(const std::string& script, const std::string& kept, std::string& reason);

}  // namespace ddafit::io
