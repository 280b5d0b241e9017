// Charts of a design scan, drawn by gnuplot from DIR/runs.csv: chi2 over each pair of
// continuous parameters, chi2 along each parameter, and the Morris ranking.
#pragma once

#include <string>

#include "inverse/scan_design.hpp"
#include "inverse/study.hpp"

namespace ddafit::app {

// chi2_map_A_B.png per pair, chi2_along_A.png per parameter, morris.png for a Morris
// design. Returns false with a reason when gnuplot is missing or fails.
bool plot_scan(const std::string& dir, const inverse::Study& study, const inverse::DesignResult& result,
               std::string& reason);

}  // namespace ddafit::app
