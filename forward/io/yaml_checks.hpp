// Checked access to a YAML tree: every failure throws SceneReadError with one line
// "FILE: KEY: PROBLEM". Shared by the scene reader and the region reader.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "forward/io/scene_reader.hpp"

namespace ddafit::io {

inline std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

inline std::string indexed(const std::string& path, size_t k) {
  return path + "[" + std::to_string(k) + "]";
}

template <class T>
inline std::string list_names(const std::vector<T>& items) {
  std::string out;
  for (const T& item : items) out += (out.empty() ? "" : ", ") + item.name;
  return out.empty() ? "none" : out;
}

// True when `s` is valid UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing past
// U+10FFFF) with no control characters (tab allowed).
inline bool is_clean_utf8(const std::string& s) {
  const auto byte = [&](size_t i) { return static_cast<unsigned char>(s[i]); };
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = byte(i);
    if (c < 0x80) {
      if ((c < 0x20 && c != '\t') || c == 0x7f) return false;
      ++i;
      continue;
    }
    int extra = 0;
    unsigned char low = 0x80, high = 0xbf;  // range of the second byte
    if (c >= 0xc2 && c <= 0xdf) {
      extra = 1;
    } else if (c >= 0xe0 && c <= 0xef) {
      extra = 2;
      if (c == 0xe0) low = 0xa0;
      if (c == 0xed) high = 0x9f;
    } else if (c >= 0xf0 && c <= 0xf4) {
      extra = 3;
      if (c == 0xf0) low = 0x90;
      if (c == 0xf4) high = 0x8f;
    } else {
      return false;
    }
    if (i + extra >= s.size()) return false;
    if (byte(i + 1) < low || byte(i + 1) > high) return false;
    for (int k = 2; k <= extra; ++k)
      if ((byte(i + k) & 0xc0) != 0x80) return false;
    i += 1 + extra;
  }
  return true;
}

// `s` for a one-line message: bytes that are not printable ASCII become \xNN, and it is
// cut at 60 characters (a 309-digit number or a megabyte of name says nothing more).
inline std::string printable(const std::string& s) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned char c : s) {
    if (out.size() >= 60) return out + "...";
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

class YamlChecks {
 public:
  explicit YamlChecks(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw SceneReadError(file_ + ": " + key + ": " + problem);
  }

  // Keys of a map, rejecting repeats, which yaml-cpp would otherwise keep silently.
  std::vector<std::string> map_keys(const YAML::Node& node, const std::string& path) const {
    if (!node.IsMap()) fail(path, "expected a map {key: value, ...}");
    std::vector<std::string> keys;
    std::set<std::string> seen;
    for (const auto& kv : node) {
      if (!kv.first.IsScalar())
        fail(path.empty() ? "(top level)" : path, "expected plain names as keys");
      keys.push_back(kv.first.Scalar());
      if (!seen.insert(keys.back()).second) fail(join(path, keys.back()), "given twice; keep one");
    }
    return keys;
  }

  // Rejects keys outside `allowed`: the usual symptom of a misspelling.
  void check_keys(const YAML::Node& node, const std::string& path,
                  const std::vector<std::string>& allowed) const {
    for (const std::string& key : map_keys(node, path)) {
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(join(path, key), "unknown key; allowed keys: " + list);
    }
  }

  YAML::Node required(const YAML::Node& map, const std::string& path, const char* key,
                      const std::string& hint) const {
    const YAML::Node n = map[key];
    if (!n) fail(join(path, key), "missing required key; " + hint);
    return n;
  }

  template <class T>
  T scalar(const YAML::Node& node, const std::string& path, const char* what) const {
    if (!node.IsScalar()) fail(path, std::string("expected ") + what);
    try {
      return node.as<T>();
    } catch (const YAML::BadConversion&) {
      fail(path, std::string("expected ") + what + ", got '" + node.Scalar() + "'");
    }
  }
  // Every number a file gives is finite: no key means infinity or "not a number", and an
  // infinite spacing or bound once reached the mesher and died by SIGFPE.
  double number(const YAML::Node& n, const std::string& path) const {
    const double v = scalar<double>(n, path, "a number");
    if (!std::isfinite(v)) fail(path, "expected a finite number, got '" + printable(n.Scalar()) + "'");
    return v;
  }
  // A length of the mesh (block size, joint spacing): positive and no larger than
  // kMaxLength; anything beyond that is no slope, and the mesher's counts overflow on it.
  static constexpr double kMaxLength = 1e6;  // m
  double length(const YAML::Node& n, const std::string& path) const {
    const double v = number(n, path);
    if (!(v > 0.0 && v <= kMaxLength)) fail(path, "is " + printable(n.Scalar()) + "; must be in (0, 1e6] m");
    return v;
  }
  // Names travel into JSON, CSV and messages: they must be valid UTF-8 without control
  // characters (an invalid byte in a region name once aborted `mesh` in the JSON writer).
  std::string text(const YAML::Node& n, const std::string& path) const {
    std::string v = scalar<std::string>(n, path, "a name");
    if (!is_clean_utf8(v)) fail(path, "the name '" + printable(v) + "' is not valid UTF-8 text without control characters");
    return v;
  }
  Vec2 vec2(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence() || n.size() != 2) fail(path, "expected a pair of numbers [x, y]");
    return Vec2(number(n[0], indexed(path, 0)), number(n[1], indexed(path, 1)));
  }
  double req_number(const YAML::Node& map, const std::string& path, const char* key,
                    const char* hint) const {
    return number(required(map, path, key, hint), join(path, key));
  }
  void opt_number(const YAML::Node& map, const std::string& path, const char* key,
                  double& target) const {
    if (const YAML::Node n = map[key]) target = number(n, join(path, key));
  }
  void list(const YAML::Node& n, const std::string& path) const {
    if (!n.IsSequence()) fail(path, "expected a list [...]");
  }

  template <class T>
  int find(const std::vector<T>& items, const std::string& name, const std::string& path,
           const char* what) const {
    for (size_t k = 0; k < items.size(); ++k)
      if (items[k].name == name) return static_cast<int>(k);
    fail(path, std::string("unknown ") + what + " '" + name + "'; defined: " + list_names(items));
  }

 private:
  std::string file_;
};

}  // namespace ddafit::io
