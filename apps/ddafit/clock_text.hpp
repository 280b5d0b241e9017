// Wall times in progress lines.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <string>

namespace ddafit::app {

// "4m07s", or "2h13m" from an hour up.
inline std::string clock_text(double seconds) {
  const long s = static_cast<long>(std::max(seconds, 0.0) + 0.5);
  return s >= 3600 ? fmt::format("{}h{:02d}m", s / 3600, (s % 3600) / 60) : fmt::format("{}m{:02d}s", s / 60, s % 60);
}

}  // namespace ddafit::app
