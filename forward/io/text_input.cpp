#include "forward/io/text_input.hpp"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ddafit::io {

std::string read_input_file(const std::string& path, std::string& problem, std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  problem.clear();
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    problem = path + ": cannot read the file: " + (ec ? ec.message() : std::string("no such file"));
    return {};
  }
  if (!fs::is_regular_file(status)) {
    problem = path + ": not a regular file (a folder, device or pipe); give a file";
    return {};
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes) {
    problem = path + ": the file is " + std::to_string(size >> 20) + " MB; inputs are limited to " +
              std::to_string(max_bytes >> 20) + " MB";
    return {};
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in) {
    problem = path + ": cannot read the file: " + std::strerror(errno);
    return {};
  }
  return text.str();
}

int yaml_document_count(const std::string& text) {
  int count = 0;
  for (const YAML::Node& document : YAML::LoadAll(text))
    if (document && !document.IsNull()) ++count;
  return count;
}

}  // namespace ddafit::io
