#include "apps/ddafit/vtk_reader.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace ddafit::app {
namespace {

// Reads the file token by token, tracking the line for messages.
class Tokens {
 public:
  explicit Tokens(std::istream& in) : in_(in) {}
  bool next(std::string& token) {
    while (true) {
      if (line_stream_ >> token) return true;
      std::string line;
      if (!std::getline(in_, line)) return false;
      ++line_;
      line_stream_.clear();
      line_stream_.str(line);
    }
  }
  std::string line_text() {
    std::string line;
    if (!std::getline(in_, line)) return {};
    ++line_;
    return line;
  }
  int line() const { return line_; }

 private:
  std::istream& in_;
  std::istringstream line_stream_;
  int line_ = 0;
};

template <class T>
bool parse(const std::string& token, T& value) {
  std::istringstream s(token);
  return static_cast<bool>(s >> value) && s.peek() == std::char_traits<char>::eof();
}

// Block counts and indices beyond this are not a snapshot ddafit wrote.
constexpr long kMaxCount = 50'000'000;

}  // namespace

std::string read_snapshot(const std::string& path, Snapshot& out) {
  out = {};
  std::ifstream file(path);
  if (!file) return path + ": cannot be opened";
  Tokens t(file);
  const auto fail = [&](const std::string& why) { return path + ": line " + std::to_string(t.line()) + ": " + why; };
  if (t.line_text().rfind("# vtk DataFile", 0) != 0) return fail("not a legacy VTK file");
  const std::string title = t.line_text();
  const auto at = title.find("t=");
  if (title.rfind("ddafit state", 0) != 0 || at == std::string::npos)
    return fail("not a ddafit state snapshot (simulate --vtk-interval writes those)");
  std::istringstream time_text(title.substr(at + 2));
  if (!(time_text >> out.time) || !std::isfinite(out.time)) return fail("no time in the title line");

  std::string token;
  long count = 0;
  while (t.next(token) && token != "POINTS") {}
  if (token != "POINTS" || !t.next(token) || !parse(token, count) || count < 3 || count > kMaxCount)
    return fail("expected 'POINTS N double'");
  t.next(token);
  out.points.resize(static_cast<size_t>(count));
  for (Vec2& p : out.points) {
    std::string x, y, z;
    double vx = 0, vy = 0;
    if (!t.next(x) || !t.next(y) || !t.next(z) || !parse(x, vx) || !parse(y, vy) || !std::isfinite(vx) ||
        !std::isfinite(vy))
      return fail("expected a point 'x y 0'");
    p = Vec2(vx, vy);
  }
  long polygons = 0, size = 0;
  if (!t.next(token) || token != "POLYGONS" || !t.next(token) || !parse(token, polygons) || polygons < 1 ||
      polygons > kMaxCount || !t.next(token) || !parse(token, size))
    return fail("expected 'POLYGONS N SIZE'");
  out.polygons.resize(static_cast<size_t>(polygons));
  for (std::vector<int>& poly : out.polygons) {
    long n = 0;
    if (!t.next(token) || !parse(token, n) || n < 3 || n > count) return fail("expected a polygon's vertex count");
    poly.resize(static_cast<size_t>(n));
    for (int& v : poly) {
      long index = -1;
      if (!t.next(token) || !parse(token, index) || index < 0 || index >= count)
        return fail("a polygon's vertex index is missing or out of range");
      v = static_cast<int>(index);
    }
  }
  // CELL_DATA: the scalars by name; fixed and speed are needed.
  while (t.next(token)) {
    if (token != "SCALARS") continue;
    std::string name, type, components, lookup, table;
    if (!t.next(name) || !t.next(type) || !t.next(components) || !t.next(lookup) || !t.next(table))
      return fail("a SCALARS header is cut short");
    std::vector<double> values(out.polygons.size());
    for (double& v : values)
      if (!t.next(token) || !parse(token, v) || !std::isfinite(v)) return fail("SCALARS " + name + ": a value is missing");
    if (name == "speed") out.speed = values;
    if (name == "fixed") {
      out.fixed.clear();
      for (double v : values) out.fixed.push_back(v != 0.0 ? 1 : 0);
    }
  }
  if (out.speed.size() != out.polygons.size() || out.fixed.size() != out.polygons.size())
    return fail("the file has no 'speed' or 'fixed' cell data");
  return {};
}

}  // namespace ddafit::app
