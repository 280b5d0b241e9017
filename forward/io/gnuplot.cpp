#include "forward/io/gnuplot.hpp"

#include <cstdlib>

namespace ddafit::io {

bool run_gnuplot(const std::string& script, const std::string& kept, std::string& reason) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    reason = "gnuplot is not installed (apt-get install gnuplot-nox); " + kept + " are written";
    return false;
  }
  if (std::system(("gnuplot '" + script + "' 2> '" + script + ".log'").c_str()) != 0) {
    reason = "gnuplot failed; see " + script + ".log";
    return false;
  }
  return true;
}

}  // namespace ddafit::io
