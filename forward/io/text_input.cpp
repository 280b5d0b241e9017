#include "forward/io/text_input.hpp"

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
  int documents = 0;
  bool content = false;  // the current document has something besides comments and blanks
  const auto marker = [](const std::string& line, const char* m) {
    return line.compare(0, 3, m) == 0 && (line.size() == 3 || line[3] == ' ' || line[3] == '\t' || line[3] == '\r');
  };
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (marker(line, "---") || marker(line, "...")) {
      if (content) ++documents;
      content = false;
      // "--- value" starts a document with content on the marker's own line.
      const size_t rest = line.find_first_not_of(" \t\r", 3);
      if (marker(line, "---") && rest != std::string::npos && line[rest] != '#') content = true;
      continue;
    }
    const size_t first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#' && line[first] != '%') content = true;
  }
  return documents + (content ? 1 : 0);
}

}  // namespace ddafit::io
