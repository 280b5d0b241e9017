// Checked access to a YAML tree: every failure throws SceneReadError with one line
// "FILE: KEY: PROBLEM". Shared by the scene reader and the region reader.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
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
  double number(const YAML::Node& n, const std::string& path) const {
    return scalar<double>(n, path, "a number");
  }
  std::string text(const YAML::Node& n, const std::string& path) const {
    return scalar<std::string>(n, path, "a name");
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
