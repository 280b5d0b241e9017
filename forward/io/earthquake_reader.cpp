#include "forward/io/earthquake_reader.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "forward/io/region_reader.hpp"
#include "forward/io/text_input.hpp"

namespace ddafit::io {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g (the records' unit)


// A time for a message: six significant digits (0.02, not 0.019999999999999997).
std::string seconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", t);
  return buf;
}

std::string at_line(const std::string& path, int line) { return "'" + path + "' line " + std::to_string(line) + ": "; }

// The fields of one CSV row split at commas, each parsed whole as a number (NaN included).
bool parse_row(const std::string& row, std::vector<double>& values, std::vector<std::string>& fields) {
  values.clear();
  fields.clear();
  std::stringstream in(row);
  std::string field;
  bool numeric = true;
  while (std::getline(in, field, ',')) {
    const size_t a = field.find_first_not_of(" \t\r"), b = field.find_last_not_of(" \t\r");
    field = a == std::string::npos ? std::string() : field.substr(a, b - a + 1);
    fields.push_back(field);
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    if (field.empty() || *end != '\0') numeric = false;
    values.push_back(v);
  }
  return numeric;
}

// Checks the new time against the record so far: increasing, and evenly spaced.
void check_time(const YamlChecks& c, const std::string& key, const std::string& where, const std::vector<double>& times,
                double t) {
  if (!std::isfinite(t)) c.fail(key, where + "time is not a finite number");
  if (t < 0.0) c.fail(key, where + "time " + seconds(t) + " s is before the run starts (t = 0)");
  if (times.empty()) return;
  if (!(t > times.back()))
    c.fail(key, where + "time " + seconds(t) + " s does not increase (the line before says " +
                    seconds(times.back()) + " s)");
  if (times.size() >= 2) {
    const double first = times[1] - times[0], step = t - times.back();
    if (std::abs(step - first) > kEvenRecordStep * first)
      c.fail(key, where + "uneven time step " + seconds(step) + " s (the record's first is " +
                      seconds(first) + " s): resample the record at an even step");
  }
}

void read_csv(const YamlChecks& c, const std::string& path, const std::string& key, double unit, GroundMotion& g) {
  std::string problem;
  std::istringstream in(read_input_file(path, problem));
  if (!problem.empty()) c.fail(key, problem);
  std::string row;
  bool header = false;
  std::vector<double> v;
  std::vector<std::string> fields;
  for (int number = 1; std::getline(in, row); ++number) {
    if (!row.empty() && row.back() == '\r') row.pop_back();
    if (row.empty() || row[0] == '#') continue;
    const std::string where = at_line(path, number);
    const bool numeric = parse_row(row, v, fields);
    if (!header) {
      if (numeric || fields.size() != 3 || fields[0] != "time" || fields[1] != "ax" || fields[2] != "ay")
        c.fail(key, where + "expected the header line time,ax,ay (ground acceleration in the scene's axes)");
      header = true;
      continue;
    }
    if (!numeric) c.fail(key, where + "expected three numbers time,ax,ay, found '" + printable(row) + "'");
    if (v.size() != 3)
      c.fail(key, where + "expected three columns time,ax,ay, found " + std::to_string(v.size()));
    check_time(c, key, where, g.time, v[0]);
    if (!std::isfinite(v[1]) || !std::isfinite(v[2])) c.fail(key, where + "ax and ay must be finite numbers");
    g.time.push_back(v[0]);
    g.acceleration.emplace_back(unit * v[1], unit * v[2]);
  }
  if (!header) c.fail(key, "'" + path + "' is empty; expected the header time,ax,ay and rows of numbers");
  if (g.time.size() < 2) c.fail(key, "'" + path + "' has fewer than two samples");
}

// NPTS and DT from the fourth header line of an AT2 file: "NPTS= 4000, DT= .0100 SEC" (NGA
// West2) or "4000 .0100 NPTS, DT" (the older NGA format).
bool parse_at2_size(const std::string& line, long& points, double& step) {
  const size_t n = line.find("NPTS"), d = line.find("DT");
  if (n == std::string::npos || d == std::string::npos) return false;
  const size_t ne = line.find('=', n), de = line.find('=', d);
  if (ne != std::string::npos && de != std::string::npos) {
    char* end = nullptr;
    points = std::strtol(line.c_str() + ne + 1, &end, 10);
    step = std::strtod(line.c_str() + de + 1, &end);
    return true;
  }
  std::istringstream in(line);
  return static_cast<bool>(in >> points >> step);
}

}  // namespace

At2Record read_at2(const YamlChecks& c, const std::string& path, const std::string& key) {
  std::string problem;
  std::istringstream in(read_input_file(path, problem));
  if (!problem.empty()) c.fail(key, problem);
  std::string line;
  long points = 0;
  At2Record r;
  int number = 0;
  for (; number < 4 && std::getline(in, line); ++number) {
  }
  if (number < 4 || !parse_at2_size(line, points, r.step))
    c.fail(key, at_line(path, 4) + "expected the PEER NGA header line 'NPTS= N, DT= STEP SEC'");
  if (!(points >= 2 && points <= 10000000)) c.fail(key, at_line(path, 4) + "NPTS must be at least 2");
  if (!(std::isfinite(r.step) && r.step > 0.0)) c.fail(key, at_line(path, 4) + "DT must be a positive number of seconds");
  r.acceleration.reserve(static_cast<size_t>(points));
  while (std::getline(in, line) && static_cast<long>(r.acceleration.size()) < points) {
    ++number;
    std::istringstream row(line);
    std::string token;
    while (row >> token && static_cast<long>(r.acceleration.size()) < points) {
      char* end = nullptr;
      const double a = std::strtod(token.c_str(), &end);
      if (*end != '\0' || !std::isfinite(a))
        c.fail(key, at_line(path, number) + "'" + printable(token) + "' is not a finite acceleration (g)");
      r.acceleration.push_back(a);
    }
  }
  if (static_cast<long>(r.acceleration.size()) < points)
    c.fail(key, "'" + path + "' ends after " + std::to_string(r.acceleration.size()) + " of the " +
                    std::to_string(points) + " samples its header (NPTS) announces");
  return r;
}

void read_earthquake(const YamlChecks& c, const YAML::Node& node, const std::string& base_dir, Scene& s) {
  if (!node.IsMap()) c.fail("earthquake", "expected a map: {record: FILE, units: g | m/s2, scale: 1.0}");
  c.check_keys(node, "earthquake", {"record", "units", "scale", "direction", "vertical"});
  GroundMotion& g = s.earthquake;
  const YAML::Node record = c.required(node, "earthquake", "record", "a CSV file time,ax,ay or a PEER .AT2 file");
  const bool at2 = record.IsScalar() && [&] {
    const std::string name = record.Scalar();
    return name.size() > 4 && (name.substr(name.size() - 4) == ".AT2" || name.substr(name.size() - 4) == ".at2");
  }();
  std::string units = at2 ? "g" : "";
  if (const YAML::Node u = node["units"]) units = c.text(u, "earthquake.units");
  if (units.empty()) c.fail("earthquake.units", "missing required key; give g or m/s2 (the record's unit)");
  if (units != "g" && units != "m/s2") c.fail("earthquake.units", "is '" + printable(units) + "'; give g or m/s2");
  if (at2 && units != "g") c.fail("earthquake.units", "a PEER .AT2 record is in g");
  const double unit = units == "g" ? kStandardGravity : 1.0;
  c.opt_number(node, "earthquake", "scale", g.scale);
  if (!(g.scale >= 0.0)) c.fail("earthquake.scale", "must be >= 0");
  if (!at2 && (node["direction"] || node["vertical"]))
    c.fail(node["direction"] ? "earthquake.direction" : "earthquake.vertical",
           "belongs to a PEER .AT2 record; a CSV record gives ax and ay itself");

  if (at2) {
    Vec2 direction(1.0, 0.0);
    if (const YAML::Node d = node["direction"]) direction = c.vec2(d, "earthquake.direction");
    if (!(direction.norm() > 0.0)) c.fail("earthquake.direction", "must not be [0, 0]");
    direction.normalize();
    const At2Record horizontal = read_at2(c, resolve_input_path(base_dir, record.Scalar()), "earthquake.record");
    At2Record vertical;
    if (const YAML::Node v = node["vertical"]) {
      vertical = read_at2(c, resolve_input_path(base_dir, c.text(v, "earthquake.vertical")), "earthquake.vertical");
      if (std::abs(vertical.step - horizontal.step) > kEvenRecordStep * horizontal.step)
        c.fail("earthquake.vertical", "its DT differs from the horizontal record's; give records at the same step");
    }
    // The shorter component ends in stillness.
    const size_t n = std::max(horizontal.acceleration.size(), vertical.acceleration.size());
    for (size_t k = 0; k < n; ++k) {
      const double h = k < horizontal.acceleration.size() ? horizontal.acceleration[k] : 0.0;
      const double v = k < vertical.acceleration.size() ? vertical.acceleration[k] : 0.0;
      g.time.push_back(static_cast<double>(k) * horizontal.step);
      g.acceleration.push_back(unit * (h * direction + Vec2(0.0, v)));
    }
  } else if (record.IsScalar()) {
    read_csv(c, resolve_input_path(base_dir, c.text(record, "earthquake.record")), "earthquake.record", unit, g);
  } else {
    // As the writer gives it: [[t, ax, ay], ...].
    c.list(record, "earthquake.record");
    for (size_t k = 0; k < record.size(); ++k) {
      const std::string key = indexed("earthquake.record", k);
      if (!record[k].IsSequence() || record[k].size() != 3) c.fail(key, "expected three numbers [t, ax, ay]");
      const double t = c.number(record[k][0], key);
      check_time(c, key, "", g.time, t);
      g.time.push_back(t);
      g.acceleration.emplace_back(unit * c.number(record[k][1], key), unit * c.number(record[k][2], key));
    }
    if (g.time.size() < 2) c.fail("earthquake.record", "give at least two samples [t, ax, ay]");
  }
}

}  // namespace ddafit::io
