// A report as one self-contained HTML file (report.html) that opens from a file share or
// an e-mail attachment: the headline sentence at the top, the body the commands already
// write as Markdown, the charts embedded as PNG data, the run's settings at the end. No
// external URL, script or style sheet: nothing to fetch, nothing to run.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace ddafit::io {

struct HtmlReport {
  std::string title;     // the page's title and first heading
  std::string headline;  // the sentence a reader quotes (bounding friction, run status)
  // The body in the subset of Markdown the reports write: '#' headings, '|' tables, '- '
  // lists, ``` blocks, **bold**, `code`, ![alt](chart.png) images, paragraphs.
  std::string markdown;
  // Shown as a table at the end: the model revision, the command, the scene or study.
  std::vector<std::pair<std::string, std::string>> settings;
  // Also embed every PNG in the folder that the body does not show (scan's charts).
  bool embed_other_charts = true;
};

// The page as text; images are read from `dir` and embedded as data: URIs, and one that
// is missing becomes a line saying so.
std::string html_report_page(const std::string& dir, const HtmlReport& report);

// Writes DIR/report.html and returns its path. Throws std::runtime_error naming the file
// when it cannot be written.
std::string write_html_report(const std::string& dir, const HtmlReport& report);

}  // namespace ddafit::io
