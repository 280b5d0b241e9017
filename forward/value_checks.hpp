// Small helpers of the input checks (validate_scene.cpp, options.cpp): a number as the
// shortest text that reads back as the same double, and the finite-and-signed tests.
#pragma once

#include <charconv>
#include <cmath>
#include <string>

namespace ddafit {

inline std::string shortest_text(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

inline bool positive(double v) { return v > 0 && std::isfinite(v); }
inline bool non_negative(double v) { return v >= 0 && std::isfinite(v); }

}  // namespace ddafit
