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

// The bounding friction as one sentence a reader can quote, e.g. "Basal friction cannot
// have dropped below mu_b = 0.146 (phi_b = 8.3 deg) at Delta chi2 <= 4 (interface
// `clay`); the best fit is mu_b = 0.158 (phi_b = 9.0 deg)." When the Delta chi2 <= 4 range
// reaches the search bound, it says that no bound was found instead.
std::string bounding_friction_sentence(const Study& study, const BoundingFriction& friction);

// The unit of a summary quantity ("m", "m/s", "s").
const char* quantity_unit(const std::string& quantity);

// Whether an observed quantity is a displacement or a speed (the charts' axes).
inline bool is_displacement(const std::string& quantity) { return quantity.find("displacement") != std::string::npos; }
inline bool is_velocity(const std::string& quantity) { return quantity.find("velocity") != std::string::npos; }

// The charts alone (report_plots.cpp): profile.png, fit.png, velocity_distance.png.
// Returns false with a reason when gnuplot is missing or fails.
bool plot_report(const std::string& dir, const Study& study, const InversionSummary& summary, std::string& reason);

}  // namespace ddafit::inverse
