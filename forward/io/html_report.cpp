#include "forward/io/html_report.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>

namespace ddafit::io {
namespace {

namespace fs = std::filesystem;

std::string escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], table[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += {table[v >> 18], table[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += {table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], '='};
  }
  return out;
}

// An image of the folder as <img> with its bytes inline, or a line saying it is missing.
// Only a plain file name inside the folder is read (no path, no URL).
std::string embedded_image(const std::string& dir, const std::string& file, const std::string& alt) {
  const bool plain = !file.empty() && file.find('/') == std::string::npos && file.find('\\') == std::string::npos &&
                     file.find(':') == std::string::npos;
  std::ifstream in(fs::path(dir) / file, std::ios::binary);
  if (!plain || !in) return "<p class=\"missing\">Chart " + escape(file) + " was not drawn.</p>\n";
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return "<figure><img alt=\"" + escape(alt) + "\" src=\"data:image/png;base64," + base64(bytes) +
         "\"><figcaption>" + escape(file) + "</figcaption></figure>\n";
}

// **bold** and `code` inside one line of text (escaped).
std::string inline_text(const std::string& line) {
  std::string out;
  for (size_t i = 0; i < line.size();) {
    if (line[i] == '`') {
      const size_t end = line.find('`', i + 1);
      if (end != std::string::npos) {
        out += "<code>" + escape(line.substr(i + 1, end - i - 1)) + "</code>";
        i = end + 1;
        continue;
      }
    }
    if (line.compare(i, 2, "**") == 0) {
      const size_t end = line.find("**", i + 2);
      if (end != std::string::npos) {
        out += "<strong>" + inline_text(line.substr(i + 2, end - i - 2)) + "</strong>";
        i = end + 2;
        continue;
      }
    }
    out += escape(std::string(1, line[i]));
    ++i;
  }
  return out;
}

std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string body = line;
  if (!body.empty() && body.front() == '|') body.erase(0, 1);
  if (!body.empty() && body.back() == '|') body.pop_back();
  std::stringstream in(body);
  std::string cell;
  while (std::getline(in, cell, '|')) {
    const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
    cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
  }
  return cells;
}

bool is_rule_row(const std::string& line) {
  return line.find_first_not_of("|-: ") == std::string::npos && line.find('-') != std::string::npos;
}

struct Body {
  std::string html;
  std::set<std::string> images;  // the file names shown
};

Body markdown_body(const std::string& dir, const std::string& markdown) {
  Body body;
  std::vector<std::string> lines;
  {
    std::stringstream in(markdown);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  std::string paragraph;
  const auto flush = [&] {
    if (!paragraph.empty()) body.html += "<p>" + paragraph + "</p>\n";
    paragraph.clear();
  };
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line.rfind("```", 0) == 0) {
      flush();
      std::string code;
      for (++i; i < lines.size() && lines[i].rfind("```", 0) != 0; ++i) code += escape(lines[i]) + "\n";
      body.html += "<pre>" + code + "</pre>\n";
    } else if (line.rfind("#", 0) == 0) {
      flush();
      const size_t level = std::min<size_t>(line.find_first_not_of('#'), 4);
      const std::string text = line.substr(line.find_first_not_of("# "));
      // The page's title is the one h1; the body's headings start at h2.
      const std::string tag = std::string("h").append(std::to_string(std::max<size_t>(level, 2)));
      body.html += "<" + tag + ">" + inline_text(text) + "</" + tag + ">\n";
    } else if (line.rfind("|", 0) == 0) {
      flush();
      body.html += "<table>\n";
      bool header = i + 1 < lines.size() && is_rule_row(lines[i + 1]);
      for (; i < lines.size() && lines[i].rfind("|", 0) == 0; ++i) {
        if (is_rule_row(lines[i])) continue;
        body.html += "<tr>";
        for (const std::string& cell : table_cells(lines[i]))
          body.html += (header ? "<th>" : "<td>") + inline_text(cell) + (header ? "</th>" : "</td>");
        body.html += "</tr>\n";
        header = false;
      }
      --i;
      body.html += "</table>\n";
    } else if (line.rfind("- ", 0) == 0) {
      flush();
      body.html += "<ul>\n";
      for (; i < lines.size() && lines[i].rfind("- ", 0) == 0; ++i) body.html += "<li>" + inline_text(lines[i].substr(2)) + "</li>\n";
      --i;
      body.html += "</ul>\n";
    } else if (line.rfind("![", 0) == 0 && line.find("](") != std::string::npos && line.back() == ')') {
      flush();
      const size_t mid = line.find("](");
      const std::string alt = line.substr(2, mid - 2), file = line.substr(mid + 2, line.size() - mid - 3);
      body.images.insert(file);
      body.html += embedded_image(dir, file, alt);
    } else if (line.find_first_not_of(' ') == std::string::npos) {
      flush();
    } else {
      if (!paragraph.empty()) paragraph += ' ';
      paragraph += inline_text(line);
    }
  }
  flush();
  return body;
}

constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}"
    ".headline{font-size:1.15em;font-weight:bold;border-left:6px solid #2a6;background:#eef8f1;padding:.8em 1em}"
    "table{border-collapse:collapse;margin:1em 0}th,td{border:1px solid #bbb;padding:.25em .6em;text-align:left}"
    "th{background:#f0f0f0}code,pre{background:#f6f6f6;font-family:monospace}pre{padding:.6em;overflow:auto}"
    "figure{margin:1em 0}img{max-width:100%}figcaption{color:#666;font-size:.9em}.missing{color:#a33}";

}  // namespace

std::string html_report_page(const std::string& dir, const HtmlReport& report) {
  // The page's title is its one h1: a body that starts with its own '# ' title drops it.
  std::string markdown = report.markdown;
  if (markdown.rfind("# ", 0) == 0) markdown.erase(0, markdown.find('\n') == std::string::npos ? markdown.size() : markdown.find('\n') + 1);
  const Body body = markdown_body(dir, markdown);
  std::string page = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
                     escape(report.title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n<h1>" +
                     escape(report.title) + "</h1>\n<p class=\"headline\" id=\"headline\">" + inline_text(report.headline) +
                     "</p>\n" + body.html;
  if (report.embed_other_charts) {
    std::vector<std::string> others;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (entry.path().extension() == ".png" && !body.images.count(name)) others.push_back(name);
    }
    std::sort(others.begin(), others.end());
    if (!others.empty()) {
      page += "<h2>Charts</h2>\n";
      for (const std::string& name : others) page += embedded_image(dir, name, name);
    }
  }
  if (!report.settings.empty()) {
    page += "<h2>Settings</h2>\n<table>\n";
    for (const auto& [name, value] : report.settings)
      page += "<tr><th>" + escape(name) + "</th><td>" + escape(value) + "</td></tr>\n";
    page += "</table>\n";
  }
  return page + "</body>\n</html>\n";
}

std::string write_html_report(const std::string& dir, const HtmlReport& report) {
  const std::string path = (fs::path(dir) / "report.html").string();
  std::ofstream out(path, std::ios::binary);
  out << html_report_page(dir, report);
  if (!out) throw std::runtime_error(path + ": cannot write the report");
  return path;
}

}  // namespace ddafit::io
