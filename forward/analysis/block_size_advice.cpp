#include "forward/analysis/block_size_advice.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace ddafit {
namespace {

std::string number(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

}  // namespace

BlockSizeAdvice advise_block_size(std::vector<LadderRung> rungs, double tolerance) {
  BlockSizeAdvice a;
  a.rungs = std::move(rungs);
  a.tolerance = tolerance;
  for (size_t k = 0; k + 1 < a.rungs.size(); ++k) {
    const LadderRung &coarse = a.rungs[k], &fine = a.rungs[k + 1];
    if (coarse.completed == 0 || fine.completed == 0 || fine.value.mean == 0.0) {
      a.change.push_back(std::numeric_limits<double>::infinity());
      a.allowed.push_back(tolerance);
      continue;
    }
    const double scale = std::abs(fine.value.mean);
    a.change.push_back(std::abs(coarse.value.mean - fine.value.mean) / scale);
    const double noise = 2.0 * std::hypot(coarse.value.standard_deviation, fine.value.standard_deviation) / scale;
    a.allowed.push_back(std::max(tolerance, noise));
    if (a.recommended < 0 && a.change.back() <= a.allowed.back()) a.recommended = static_cast<int>(k);
  }
  if (a.rungs.size() < 2) {
    a.verdict = "give at least two block sizes: the advice compares each with the next finer one";
  } else if (a.recommended >= 0) {
    const size_t k = static_cast<size_t>(a.recommended);
    a.verdict = "use block_size " + number(a.rungs[k].block_size, "%g") + " m: its answer is within " +
                number(100.0 * a.change[k], "%.1f") + " % of the next finer (" +
                number(a.rungs[k + 1].block_size, "%g") + " m), inside the " + number(100.0 * a.allowed[k], "%.1f") +
                " % allowed" + (a.allowed[k] > a.tolerance ? " (the runs' own spread, wider than the tolerance)" : "");
  } else {
    a.verdict = "the answer keeps moving with block size: no size of the ladder is within the tolerance of the next "
                "finer one, so the finest (" + number(a.rungs.back().block_size, "%g") +
                " m) is the best guess, not a converged answer (the seed found d_c scales with the block length: a "
                "finer mesh is a different model, not only a more accurate one)";
  }
  return a;
}

}  // namespace ddafit
