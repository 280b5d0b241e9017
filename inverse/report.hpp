// The report of an inversion in DIR: report.json (every number), report.md (for people)
// and PNG charts drawn by gnuplot (skipped with a note when gnuplot is missing).
#pragma once

#include <string>
#include <vector>

#include "inverse/inversion.hpp"
#include "inverse/study.hpp"

namespace ddafit::inverse {

// Writes report.json and report.md; draws the charts. Returns notes about charts that
// could not be drawn. Throws std::runtime_error when a file cannot be written.
std::vector<std::string> write_report(const std::string& dir, const Study& study, const InversionSummary& summary);

// The charts alone (report_plots.cpp): profile.png, fit.png, velocity_distance.png.
// Returns false with a reason when gnuplot is missing or fails.
bool plot_report(const std::string& dir, const Study& study, const InversionSummary& summary, std::string& reason);

}  // namespace ddafit::inverse
