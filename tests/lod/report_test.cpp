// The LOD report: its charts, and the whole page loaded in headless Chromium (Debian's `chromium`)
// with no console message — the report carries no script, so any console output means something is
// broken — and every image it shows present. Skipped with a message where Chromium is absent.
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "base/markup_escape.h"
#include "lod/comparison.h"
#include "lod/report.h"
#include "tests/common/read_only_folder.h"
#include "tests/common/run_command.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;
using testing::run_command;
using testing::slurp;
using testing::TempDir;

const fs::path kManifest = fs::path(SVBRDF_BINARY_DIR) / "scenes" / "lod" / "manifest.json";

TEST(LodReport, ChartPointsLieInThePlot) {
  const std::string svg = svg_chart("t <&>", "y", {{"a", "#000", false, {1, 4, 16, 1024}, {1e-3, 1e-2, 0.5, 2.0}},
                                                   {"b", "#111", true, {1, 1024}, {0.0, 1e-4}}},
                                    true, 320, 234);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 6), "</svg>");
  EXPECT_NE(svg.find("t &lt;&amp;&gt;"), std::string::npos);
  // Every circle inside the plot rectangle [58, 310] × [22, 170] (234 − 64); the zero of the log
  // series skipped.
  const std::regex circle("<circle cx=\"([0-9.]+)\" cy=\"([0-9.]+)\"");
  int n = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it, ++n) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    EXPECT_GE(x, 58.0 - 1e-6);
    EXPECT_LE(x, 310.0 + 1e-6);
    EXPECT_GE(y, 22.0 - 1e-6);
    EXPECT_LE(y, 170.0 + 1e-6);
  }
  EXPECT_EQ(n, 5);
  EXPECT_EQ(markup_escape("a<b>&\"c\""), "a&lt;b&gt;&amp;&quot;c&quot;");
}

// The x labels of a chart over 1× to 16384× (the LOD scenes' distances), measured in DejaVu Sans at the
// page's 11 px by FreeType (OpenImageIO's text_size): none overlaps the next, all lie inside the chart,
// and the farthest distance is labelled.
TEST(LodReport, DistanceLabelsDoNotOverlap) {
  std::vector<double> x, y;
  for (double d = 1; d <= 16384; d *= 4) x.push_back(d), y.push_back(1e-3 * d);
  const std::string svg = svg_chart("relative MSE", "relative MSE", {{"brdf", "#000", false, x, y}}, true, 320, 234);
  const std::regex label("<text x=\"([0-9.]+)\" y=\"[0-9.]+\" class=\"tx\">([0-9]+)×</text>");
  std::vector<std::pair<double, double>> spans;  // [left, right] of each label, in order
  std::string last;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator(); ++it) {
    const std::string text = (*it)[2].str() + "×";
    const OIIO::ROI size = OIIO::ImageBufAlgo::text_size(text, 11, "DejaVuSans");
    ASSERT_TRUE(size.defined()) << "no DejaVu Sans font to measure with (Debian: fonts-dejavu-core)";
    const double cx = std::stod((*it)[1]);
    spans.emplace_back(cx - size.width() / 2.0, cx + size.width() / 2.0);
    last = text;
  }
  ASSERT_GE(spans.size(), 3u) << svg;
  EXPECT_EQ(last, "16384×");
  for (std::size_t i = 0; i < spans.size(); ++i) {
    EXPECT_GE(spans[i].first, 0.0) << i;
    EXPECT_LE(spans[i].second, 320.0) << i;
    if (i > 0) {
      EXPECT_GE(spans[i].first - spans[i - 1].second, 2.0) << "labels " << i - 1 << " and " << i << " overlap";
    }
  }
}

// Loads file:// `page` in headless Chromium; returns its stderr (console messages are logged there
// as "…:CONSOLE:…" lines) and the DOM it rendered.
struct Loaded {
  int status = -1;
  std::string log, dom;
};
Loaded load_in_chromium(const fs::path& page, const TempDir& dir) {
  const std::string cmd = "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
                          "--disable-background-networking --disable-component-update --disable-sync "
                          "--user-data-dir='" + (dir / "profile").string() + "' --enable-logging=stderr --v=0 "
                          "--dump-dom 'file://" + page.string() + "'";
  const auto r = run_command(cmd, dir.path());
  return {r.status, r.err, r.out};
}

std::vector<std::string> console_lines(const std::string& log) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t nl; (nl = log.find('\n', start)) != std::string::npos; start = nl + 1) {
    const std::string line = log.substr(start, nl - start);
    if (line.find(":CONSOLE") != std::string::npos) out.push_back(line);
  }
  return out;
}

bool have_chromium() { return std::system("command -v chromium >/dev/null 2>&1") == 0; }

// The harness itself can fail: a page with a script error is caught.
TEST(LodReport, ChromiumHarnessCatchesConsoleErrors) {
  if (!have_chromium()) GTEST_SKIP() << "chromium is not installed (Debian package `chromium`): cannot load the report headless";
  const TempDir dir;
  {
    std::ofstream f(dir / "bad.html");
    f << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>bad</title></head><body>"
         "<script>notDefinedAnywhere();</script></body></html>";
  }
  const Loaded l = load_in_chromium(dir / "bad.html", dir);
  EXPECT_EQ(l.status, 0) << l.log;
  const auto lines = console_lines(l.log);
  ASSERT_EQ(lines.size(), 1u) << l.log;
  EXPECT_NE(lines[0].find("notDefinedAnywhere"), std::string::npos) << lines[0];
}

TEST(LodReport, RendersInHeadlessChromiumWithoutConsoleErrors) {
  if (!have_chromium()) GTEST_SKIP() << "chromium is not installed (Debian package `chromium`): cannot load the report headless";
  const LodManifest m = read_lod_manifest(kManifest);
  LodOptions o;
  o.spp = 16;
  o.cases = {"metal-tray-steel"};
  o.lights = {"sun-45"};
  o.min_distance = 256;
  o.max_distance = 1024;
  const LodResults r = run_lod_comparison(m, o);
  ASSERT_EQ(r.shots.size(), 4u);  // head-on and mirror, 256× and 1024×
  const TempDir dir;
  LodReportInfo info;
  info.size_name = "test";
  const fs::path index = write_lod_report(r, m, dir / "report", info);
  ASSERT_TRUE(fs::exists(index));

  // Every image the page shows exists beside it.
  const std::string html = slurp(index);
  const std::regex src("<img src=\"([^\"]+)\"");
  int images = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), src); it != std::sregex_iterator(); ++it, ++images)
    EXPECT_TRUE(fs::exists(index.parent_path() / (*it)[1].str())) << (*it)[1];
  EXPECT_EQ(images, int(r.shots.size() * (1 + 2 * r.filters.size())));

  const Loaded l = load_in_chromium(index, dir);
  EXPECT_EQ(l.status, 0) << l.log;
  EXPECT_TRUE(console_lines(l.log).empty()) << console_lines(l.log).front();
  // It rendered the document: three charts per scene, the tables and the images.
  EXPECT_NE(l.dom.find("<title>svbrdf"), std::string::npos) << l.dom.substr(0, 300);
  std::size_t svgs = 0;
  for (std::size_t p = 0; (p = l.dom.find("<svg xmlns", p)) != std::string::npos; ++p) ++svgs;
  EXPECT_EQ(svgs, 2u * 3u);  // two scenes (head-on and mirror)
  EXPECT_NE(l.dom.find("<table class=\"strip\">"), std::string::npos);
}

// svbrdf-lod-report: bad input is one line on stderr and exit 2, and writes nothing; a small run
// writes the report.
TEST(LodReport, ProgramBadInputAndASmallRun) {
  const TempDir dir;
  const std::string exe = SVBRDF_LOD_REPORT;
  const std::string out = " --out '" + (dir / "r").string() + "'";
  for (const std::string& args : {std::string("--bogus"), std::string("--case nope"), std::string("--light dusk"),
                                  std::string("--manifest /nonexistent/manifest.json"), std::string("--spp 0"),
                                  std::string("--footprint-scale -1"), std::string("--max-distance 0"),
                                  std::string("--min-distance -4"), std::string("--footprint-scale 1e30"),
                                  std::string("--spp 1e10")}) {
    const auto r = run_command(exe + " " + args + out, dir.path());
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "r")) << args;
  }
  const auto ok = run_command(exe + " --spp 4 --case printed-paper-text --light sun-0 --min-distance 1024 -q" + out, dir.path());
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_EQ(ok.err, "");
  EXPECT_TRUE(fs::exists(dir / "r" / "index.html"));
  // The page says which MIP level the distance reads: at 4 samples per pixel each sample's footprint is
  // 1/√4 = 1/2 of the pixel's, so 1024× reads log₂(512) = 9, clamped to the 256² textures' 8.
  const std::string html = slurp(dir / "r" / "index.html");
  EXPECT_NE(html.find("scaled by 0.5 "), std::string::npos);
  const std::size_t said = html.find("Under the MIP");
  ASSERT_NE(said, std::string::npos);
  EXPECT_NE(html.find("level 8 at 1024×", said), std::string::npos) << html.substr(said, 600);
  // With --footprint-scale 1 each sample filters the whole pixel: k× reads level log₂ k (64× level 6).
  const auto whole = run_command(exe + " --spp 4 --footprint-scale 1 --case printed-paper-text --light sun-0 --min-distance 1024 -q" +
                                     " --out '" + (dir / "r1").string() + "'", dir.path());
  EXPECT_EQ(whole.status, 0) << whole.err;
  const std::string html1 = slurp(dir / "r1" / "index.html");
  EXPECT_NE(html1.find("scaled by 1 "), std::string::npos);
  EXPECT_NE(html1.find("level 6 at 64×"), std::string::npos);
}

// A report folder the machine does not let us write: one line and exit 1 (the machine's failure, not
// bad input), before the comparison's renders rather than after them.
TEST(LodReport, AnUnwritableReportFolderIsExit1BeforeRendering) {
  const TempDir dir;
  const testing::ReadOnlyFolder read_only(dir.path());
  if (read_only.path().empty()) GTEST_SKIP() << "no folder here that refuses new files";
  const fs::path& ro = read_only.path();
  // Without -q each render says so on stderr: none may come.
  const auto r = run_command(std::string(SVBRDF_LOD_REPORT) + " --spp 4 --case printed-paper-text --light sun-0 --min-distance 1024 --out '" +
                                 (ro / "r").string() + "'",
                             dir.path());
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("svbrdf-lod-report: " + (ro / "r").string(), 0), 0u) << r.err;
}

}  // namespace
}  // namespace svbrdf
