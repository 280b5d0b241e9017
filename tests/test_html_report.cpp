// report.html (issue "ddafit from Python, its reports in a browser …"): one self-contained
// file that opens with no server and no network. The page is checked as text (nothing it
// would fetch, the headline present, the charts inline), then as Chromium draws it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "forward/io/html_report.hpp"
#include "tests/cli_run.hpp"

namespace ddafit {
namespace {

using ddafit_test::slurp;
namespace fs = std::filesystem;

const std::string kCases = DDAFIT_CASES_DIR;

fs::path fresh(const std::string& tag) {
  const fs::path dir = fs::path(DDAFIT_TEST_TMP) / tag;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Every attribute that makes a browser fetch something (src, href, url(), @import) must
// point at inline data: nothing outside the file is read when it opens.
void expect_self_contained(const std::string& page) {
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(page.find("href="), std::string::npos);
  EXPECT_EQ(page.find("@import"), std::string::npos);
  EXPECT_EQ(page.find("url("), std::string::npos);
  // (A scan by hand: std::regex recurses per character and overflows the stack on a chart.)
  for (size_t at = page.find("src=\""); at != std::string::npos; at = page.find("src=\"", at + 5))
    EXPECT_EQ(page.compare(at + 5, 22, "data:image/png;base64,"), 0) << page.substr(at, 80);
}

TEST(HtmlReport, ThePageCarriesItsChartsInlineAndEscapesText) {
  const fs::path dir = fresh("html_page");
  std::ofstream(dir / "a.png", std::ios::binary) << "Man";  // base64 "TWFu" (RFC 4648 example)
  std::ofstream(dir / "b.png", std::ios::binary) << "Ma";   // "TWE="
  std::ofstream(dir / "c.png", std::ios::binary) << "M";    // "TQ=="
  io::HtmlReport r;
  r.title = "Back-analysis: study <1>";
  r.headline = "Basal friction cannot have dropped below mu_b = 0.160 & stayed there.";
  r.markdown = "# Back-analysis: study <1>\n\nSome **bold** and `code`.\n\n| a | b |\n|---|---|\n| 1 | <x> |\n\n"
               "- one\n- two\n\n![first](a.png)\n![gone](missing.png)\n![outside](../a.png)\n";
  r.settings = {{"model revision", "2026-11-26.1"}};
  const std::string page = io::html_report_page(dir.string(), r);
  expect_self_contained(page);
  EXPECT_NE(page.find("data:image/png;base64,TWFu\""), std::string::npos);
  // Charts the body does not show are added: b.png and c.png, with their padding.
  EXPECT_NE(page.find("data:image/png;base64,TWE=\""), std::string::npos);
  EXPECT_NE(page.find("data:image/png;base64,TQ==\""), std::string::npos);
  EXPECT_NE(page.find("Chart missing.png was not drawn"), std::string::npos);
  EXPECT_NE(page.find("Chart ../a.png was not drawn"), std::string::npos);  // only files of the folder
  EXPECT_NE(page.find("mu_b = 0.160 &amp; stayed there."), std::string::npos);
  EXPECT_NE(page.find("<td>&lt;x&gt;</td>"), std::string::npos);
  EXPECT_NE(page.find("<th>a</th>"), std::string::npos);
  EXPECT_NE(page.find("<strong>bold</strong>"), std::string::npos);
  EXPECT_NE(page.find("<li>two</li>"), std::string::npos);
  // One h1: the body's own '# ' title is dropped.
  EXPECT_EQ(page.find("<h1>", page.find("<h1>") + 1), std::string::npos);
}

bool have_gnuplot() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

TEST(HtmlReport, SimulateWithPlotsWritesAReportWithItsChartsInside) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed: the charts are not drawn";
  const fs::path dir = fresh("html_simulate");
  const auto r = ddafit_test::ddafit("simulate " + kCases + "/verification/incline_i5.yaml --plots --quiet --out " +
                                         (dir / "out").string(), "html_simulate/cmd");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string page = slurp(dir / "out" / "report.html");
  expect_self_contained(page);
  EXPECT_NE(page.find("id=\"headline\">Point"), std::string::npos);
  EXPECT_NE(page.find("<img alt=\"velocity against distance\" src=\"data:image/png;base64,iVBORw0KGgo"),
            std::string::npos);  // a PNG's signature, base64
  EXPECT_EQ(page.find("was not drawn"), std::string::npos);
}

TEST(HtmlReport, InvertWritesTheBoundingFrictionSentenceAtTheTop) {
  const fs::path dir = fresh("html_invert");
  const auto r = ddafit_test::ddafit("invert " + kCases + "/inverse/twin_study.yaml --quiet --out " +
                                         (dir / "out").string(), "html_invert/cmd");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string page = slurp(dir / "out" / "report.html");
  expect_self_contained(page);
  const size_t headline = page.find("id=\"headline\">Basal friction");
  ASSERT_NE(headline, std::string::npos) << page.substr(0, 2000);
  // At the top: before the body's first section.
  EXPECT_LT(headline, page.find("<h2>"));
  EXPECT_NE(page.find("2026-"), std::string::npos);  // the model revision among the settings
}

// Chromium as a user would open the file: headless, as root without its sandbox.
std::string chromium() {
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"})
    if (std::system((std::string("command -v ") + name + " > /dev/null 2>&1").c_str()) == 0) return name;
  return {};
}

int run_chromium(const std::string& browser, const std::string& args, const fs::path& out) {
  const std::string cmd = browser + " --headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run " + args +
                          " > " + out.string() + " 2> " + out.string() + ".err";
  return std::system(cmd.c_str());
}

TEST(HtmlReport, ChromiumDrawsTheReportWithTheSentenceInItsDom) {
  const std::string browser = chromium();
  if (browser.empty()) GTEST_SKIP() << "Chromium is not installed (scripts/install-deps.sh installs it)";
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot is not installed: the charts are not drawn";
  const fs::path dir = fresh("html_chromium");
  const auto r = ddafit_test::ddafit("simulate " + kCases + "/verification/incline_i5.yaml --plots --quiet --out " +
                                         (dir / "out").string(), "html_chromium/cmd");
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path report = fs::absolute(dir / "out" / "report.html");
  const fs::path blank = dir / "blank.html";
  std::ofstream(blank) << "<!DOCTYPE html><html><body></body></html>\n";
  const std::string size = "--window-size=1200,1600 ";
  ASSERT_EQ(run_chromium(browser, size + "--screenshot=" + (dir / "report.png").string() + " file://" + report.string(),
                         dir / "shot.log"), 0);
  ASSERT_EQ(run_chromium(browser, size + "--screenshot=" + (dir / "blank.png").string() + " file://" +
                                      fs::absolute(blank).string(), dir / "blank.log"), 0);
  ASSERT_EQ(run_chromium(browser, "--dump-dom file://" + report.string(), dir / "dom.html"), 0);
  // A drawn page (text, tables, charts) compresses far worse than a white one of the same
  // size: a blank 1200 x 1600 screenshot is a few kB.
  ASSERT_TRUE(fs::exists(dir / "report.png") && fs::exists(dir / "blank.png"));
  EXPECT_GT(fs::file_size(dir / "report.png"), 5 * fs::file_size(dir / "blank.png"));
  const std::string dom = slurp(dir / "dom.html");
  const std::string page = slurp(report);
  const size_t at = page.find("id=\"headline\">");
  ASSERT_NE(at, std::string::npos);
  const std::string sentence = page.substr(at + 14, page.find("</p>", at) - at - 14);
  EXPECT_NE(dom.find(sentence), std::string::npos) << sentence;
}

}  // namespace
}  // namespace ddafit
