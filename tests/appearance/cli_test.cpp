// svbrdf-brdf as a user runs it (brdf-models.md, last section): the Done-when value, the output
// formats, and bad input (one line on stderr, exit 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "appearance/registry.h"
#include "test_models.h"
#include "tests/common/run_command.h"
#include "textures/image.h"
#include "tests/common/test_paths.h"

namespace svbrdf::testing {
namespace {

using CliRun = CommandResult;

// Runs `svbrdf-brdf ARGS` through the shell with `input` on stdin.
CliRun run(const std::string& args, const std::string& input = "") {
  const TempDir dir;
  return run_command(std::string("'") + SVBRDF_BRDF_EXE + "' " + args, dir.path(), input);
}

int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(Cli, DoneWhenValue) {
  const CliRun r = run("eval gltf --param base_color=0.5 --param roughness=0.5", "0 0 1 0 0 1\n");
  ASSERT_EQ(r.status, 0) << r.err;
  // α = 0.25: f = 0.96·0.5/π + 0.04·(1/4)·1/(π α²) (Appendix B at normal incidence, by hand).
  const double expected = 0.96 * 0.5 / M_PI + 0.04 * 0.25 / (M_PI * 0.0625);
  double v[3];
  ASSERT_EQ(std::sscanf(r.out.c_str(), "%lf %lf %lf", &v[0], &v[1], &v[2]), 3) << r.out;
  for (double x : v) EXPECT_NEAR(x, expected, 1e-6);
  EXPECT_NEAR(expected, 0.203718, 1e-6);
}

TEST(Cli, EvalPdfSampleAlbedoFormats) {
  const CliRun e = run("eval lambert --param albedo=0.2,0.4,0.6", "# comment\n\n0 0 1 0 0 1\n  0.6 0 0.8 0 0.6 0.8\n");
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_EQ(lines(e.out), 2) << "blank and # lines are skipped";
  double r, g, b;
  ASSERT_EQ(std::sscanf(e.out.c_str(), "%lf %lf %lf", &r, &g, &b), 3);
  EXPECT_NEAR(g, 0.4 / M_PI, 1e-8);
  const CliRun p = run("pdf lambert --param albedo=0.5", "0 0 1 0 0 1\n");
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_NEAR(std::stod(p.out), 0.5 / M_PI, 1e-8) << "scatter probability 0.5 × cos/π";
  const CliRun s = run("sample lambert --param albedo=0.2 --impulse mirror:0.4 --wo 0,0.6,0.8 --count 2000 --seed 7");
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_EQ(lines(s.out), 2000);
  std::istringstream in(s.out);
  std::string line;
  int impulses = 0;
  while (std::getline(in, line)) {
    double x[7];
    char kind[16];
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf %lf %lf %lf %lf %15s", &x[0], &x[1], &x[2], &x[3], &x[4], &x[5], &x[6], kind), 8)
        << line;
    const std::string k = kind;
    EXPECT_TRUE(k == "finite" || k == "impulse" || k == "absorbed") << k;
    if (k == "impulse") {
      ++impulses;
      EXPECT_NEAR(x[1], -0.6, 1e-6) << "the mirror direction";
    }
  }
  EXPECT_NEAR(impulses / 2000.0, 0.4, 0.05);
  EXPECT_EQ(run("sample lambert --wo 0,0,1 --count 3 --seed 7").out, run("sample lambert --wo 0,0,1 --count 3 --seed 7").out)
      << "deterministic for a seed";
  const CliRun a = run("albedo lambert --param albedo=0.3 --impulse mirror:0.4 --theta-o 30");
  ASSERT_EQ(a.status, 0) << a.err;
  double f[3], imp[3];
  ASSERT_EQ(std::sscanf(a.out.c_str(), "finite %lf %lf %lf\nimpulse %lf %lf %lf", &f[0], &f[1], &f[2], &imp[0], &imp[1], &imp[2]), 6)
      << a.out;
  EXPECT_NEAR(f[0], 0.3, 1e-4);
  EXPECT_NEAR(imp[0], 0.4, 1e-6);
}

// sample --stdin samples for the direction and at the numbers each line gives: the line the model's own
// sample() gives for them, printed as the seeded form prints it.
TEST(Cli, SampleAtTheNumbersOnStdin) {
  const CliRun s = run("sample lambert --param albedo=0.2 --impulse mirror:0.4 --stdin",
                       "0 0.6 0.8 0.25 0.5 0.75\n# comment\n\n0 0 1 0.9 0.125 0.5\n0.6 0 0.8 0.5 0.7 0.3\n");
  ASSERT_EQ(s.status, 0) << s.err;
  const auto bsdf = make_model("lambert", {"albedo=0.2"}, {"mirror:0.4"});
  const std::array<std::pair<glm::vec3, SampleU>, 3> cases = {{{{0.0f, 0.6f, 0.8f}, {0.25f, 0.5f, 0.75f}},
                                                              {{0.0f, 0.0f, 1.0f}, {0.9f, 0.125f, 0.5f}},
                                                              {{0.6f, 0.0f, 0.8f}, {0.5f, 0.7f, 0.3f}}}};
  std::string expected;
  for (const auto& [wo, u] : cases) {
    const BsdfSample b = bsdf->sample(wo, u);
    char line[256];
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %s\n", double(b.wi.x), double(b.wi.y), double(b.wi.z),
                  double(b.pdf), double(b.weight.x), double(b.weight.y), double(b.weight.z),
                  b.kind == SampleKind::finite ? "finite" : b.kind == SampleKind::impulse ? "impulse" : "absorbed");
    expected += line;
  }
  EXPECT_EQ(s.out, expected);
  // Too few or too many numbers, u outside [0, 1) (1e300 beyond float's range; 0.99999999 rounds to 1 as
  // a float), a NaN, a wo that is not unit length.
  for (const char* bad : {"0 0 1 0.5 0.5\n", "0 0 1 0.5 0.5 0.5 0.5\n", "0 0 1 0.5 0.5 1\n", "0 0 1 0.5 -0.1 0.5\n",
                          "0 0 1 1e300 0.5 0.5\n", "0 0 1 0.99999999 0.5 0.5\n", "0 0 1 0.5 nan 0.5\n",
                          "0 0 2 0.5 0.5 0.5\n"}) {
    const CliRun r = run("sample lambert --stdin", std::string("0 0 1 0.5 0.5 0.5\n") + bad);
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("svbrdf-brdf: stdin line 2: ", 0), 0u) << r.err;
  }
  for (const char* both : {"--wo 0,0,1", "--count 3", "--seed 1"})
    EXPECT_EQ(run(std::string("sample lambert --stdin ") + both, "0 0 1 0.5 0.5 0.5\n").status, 2) << both;
  const CliRun no_wo = run("sample lambert --count 1");
  EXPECT_EQ(no_wo.status, 2);
  EXPECT_EQ(no_wo.err, "svbrdf-brdf: sample: --wo is required (or --stdin)\n");
}

TEST(Cli, PlotsAreWrittenAsSvg) {
  const auto dir = std::filesystem::temp_directory_path() / ("svbrdf_cli_plot_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const CliRun p = run("plot gltf --param roughness=0.3 --impulse mirror:0.2 --theta-i 40 --out '" + (dir / "g.svg").string() + "'");
  ASSERT_EQ(p.status, 0) << p.err;
  std::ifstream f(dir / "g.svg");
  std::stringstream s;
  s << f.rdbuf();
  EXPECT_EQ(s.str().rfind("<?xml", 0), 0u);
  EXPECT_NE(s.str().find("<polyline"), std::string::npos);
  EXPECT_NE(s.str().find("stroke=\"black\""), std::string::npos) << "the BSDF curve";
  EXPECT_NE(s.str().find("<polygon"), std::string::npos) << "an impulse arrow";
  EXPECT_NE(s.str().find("</svg>"), std::string::npos);
  const CliRun fr = run("fresnel --ior 1.5 --out '" + (dir / "f.svg").string() + "'");
  ASSERT_EQ(fr.status, 0) << fr.err;
  double diff, at;
  ASSERT_EQ(std::sscanf(fr.out.c_str(), "max |exact - schlick| %lf at %lf deg", &diff, &at), 2) << fr.out;
  EXPECT_NEAR(diff, 0.0357, 2e-4);
  EXPECT_NEAR(at, 84.97, 0.05);
  EXPECT_TRUE(std::filesystem::exists(dir / "f.svg"));
  EXPECT_EQ(run("fresnel --eta 0.2,0.92,1.1 --k 3.9,2.45,2.14 --out '" + (dir / "c.svg").string() + "'").status, 0);
  // Bad output names and bad options leave nothing behind.
  const CliRun jpeg = run("plot lambert --theta-i 40 --out '" + (dir / "x.jpg").string() + "'");
  EXPECT_EQ(jpeg.status, 2);
  EXPECT_EQ(lines(jpeg.err), 1) << jpeg.err;
  EXPECT_EQ(run("plot lambert --theta-i 400 --out '" + (dir / "y.svg").string() + "'").status, 2);
  EXPECT_EQ(run("fresnel --ior 1.5 --eta 1 --k 1 --out '" + (dir / "z.svg").string() + "'").status, 2);
  EXPECT_EQ(run("plot lambert --theta-i 40 --out '" + (dir / "missing" / "w.svg").string() + "'").status, 2);
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 3) << "g.svg, f.svg, c.svg and no temporaries";
  std::filesystem::remove_all(dir);
}

// The segments of every SVG polyline stroked in `color`. Found with find, not std::regex: libstdc++'s
// regex recurses once a character, and a polyline's points run to tens of kilobytes.
std::vector<std::array<double, 4>> svg_segments(const std::string& svg, const std::string& color) {
  std::vector<std::array<double, 4>> segments;
  const std::string open = "<polyline points=\"", stroke = "\" fill=\"none\" stroke=\"" + color + "\"";
  for (std::size_t at = svg.find(open); at != std::string::npos; at = svg.find(open, at + 1)) {
    const std::size_t begin = at + open.size(), end = svg.find('"', begin);
    if (end == std::string::npos || svg.compare(end, stroke.size(), stroke) != 0) continue;
    std::istringstream points(svg.substr(begin, end - begin));
    std::vector<double> xy;
    for (double x, y; points >> x && points.get() == ',' && points >> y;) xy.insert(xy.end(), {x, y});
    for (std::size_t i = 2; i + 1 < xy.size(); i += 2) segments.push_back({xy[i - 2], xy[i - 1], xy[i], xy[i + 1]});
  }
  return segments;
}

double distance_to(const std::vector<std::array<double, 4>>& segments, double px, double py) {
  double best = 1e300;
  for (const auto& [ax, ay, bx, by] : segments) {
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    const double t = len2 > 0 ? std::clamp(((px - ax) * dx + (py - ay) * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(px - ax - t * dx, py - ay - t * dy));
  }
  return best;
}

// A plot named .png is the same figure in pixels: the SVG's size, the BSDF curve dark where the SVG's
// black polyline runs, and the sampling density's blue nowhere but along the SVG's blue polyline.
TEST(Cli, PlotsAreWrittenAsPng) {
  // Not a TempDir: run() makes the test's own for each command.
  const auto dir = std::filesystem::temp_directory_path() / ("svbrdf_cli_png_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string args = "plot gltf --param roughness=0.3 --impulse mirror:0.2 --theta-i 40 --out ";
  ASSERT_EQ(run(args + "'" + (dir / "g.svg").string() + "'").status, 0);
  const CliRun p = run(args + "'" + (dir / "g.png").string() + "'");
  ASSERT_EQ(p.status, 0) << p.err;
  std::ifstream f(dir / "g.svg");
  std::stringstream s;
  s << f.rdbuf();
  const std::string svg = s.str();
  std::smatch size;
  ASSERT_TRUE(std::regex_search(svg, size, std::regex("<svg [^>]*width=\"([0-9.]+)\" height=\"([0-9.]+)\"")));
  const Image png = read_image(dir / "g.png");
  EXPECT_EQ(png.width, int(std::ceil(std::stod(size[1].str()))));
  EXPECT_EQ(png.height, int(std::ceil(std::stod(size[2].str()))));
  ASSERT_GE(png.channels, 3);

  const auto black = svg_segments(svg, "black"), blue = svg_segments(svg, "#1f4fd8");
  ASSERT_GT(black.size(), 100u);
  ASSERT_GT(blue.size(), 100u);
  // Along the black curve (its segments' midpoints): dark pixels, except where an arrow drawn later
  // crosses it.
  int dark = 0;
  for (const auto& [ax, ay, bx, by] : black) {
    const int x = int((ax + bx) / 2), y = int((ay + by) / 2);
    if (x < 0 || y < 0 || x >= png.width || y >= png.height) continue;
    dark += std::max({png.at(x, y, 0), png.at(x, y, 1), png.at(x, y, 2)}) < 0.4f;
  }
  EXPECT_GT(dark, int(0.95 * double(black.size())));
  // Every clearly blue pixel below the legend (whose line "pdf(...)" is blue text) lies on the blue curve.
  int blue_pixels = 0;
  for (int y = 75; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      if (png.at(x, y, 2) > 0.6f && png.at(x, y, 2) - png.at(x, y, 0) > 0.4f) {
        ++blue_pixels;
        EXPECT_LT(distance_to(blue, x + 0.5, y + 0.5), 2.0) << "a blue pixel at " << x << "," << y;
      }
  EXPECT_GT(blue_pixels, 200);

  ASSERT_EQ(run("fresnel --ior 1.5 --out '" + (dir / "f.png").string() + "'").status, 0);
  const Image fresnel = read_image(dir / "f.png");
  EXPECT_GT(fresnel.width, 100);
  EXPECT_GT(fresnel.height, 100);
  std::filesystem::remove_all(dir);
}

TEST(Cli, BadInputExitsTwoWithOneLine) {
  const CliRun malformed = run("eval lambert", "0 0 1 0 0 1\n0 0 1 0 0\n");
  EXPECT_EQ(malformed.status, 2);
  EXPECT_NE(malformed.err.find("line 2"), std::string::npos) << malformed.err;
  EXPECT_EQ(lines(malformed.err), 1) << malformed.err;
  EXPECT_EQ(run("eval lambert", "0 0 1 0 0 1 7\n").status, 2);
  EXPECT_EQ(run("eval lambert", "0 0 nan 0 0 1\n").status, 2);
  const CliRun not_unit = run("pdf lambert", "\n1 0 1 0 0 1\n");
  EXPECT_EQ(not_unit.status, 2);
  EXPECT_NE(not_unit.err.find("line 2"), std::string::npos) << not_unit.err;
  const CliRun unknown = run("eval velvet", "0 0 1 0 0 1\n");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.err.find("velvet"), std::string::npos);
  EXPECT_EQ(lines(unknown.err), 1);
  EXPECT_EQ(run("eval gltf --param roughness=nan", "0 0 1 0 0 1\n").status, 2);
  EXPECT_EQ(run("eval microfacet --param alpha=0", "0 0 1 0 0 1\n").status, 2);
  EXPECT_EQ(run("eval lambert --param albedo=-0.5", "0 0 1 0 0 1\n").status, 2);
  EXPECT_EQ(run("eval lambert --param sheen=1", "0 0 1 0 0 1\n").status, 2);
  EXPECT_EQ(run("sample lambert --wo 0,0,2 --count 1").status, 2);
  EXPECT_EQ(run("sample lambert --wo 0,0 --count 1").status, 2);
  EXPECT_EQ(run("sample lambert --wo 0,0,1 --count -3").status, 2);
  EXPECT_EQ(run("albedo lambert --theta-o 91").status, 2);
  EXPECT_EQ(run("albedo lambert").status, 2) << "--theta-o is required";
  EXPECT_EQ(run("").status, 2) << "a subcommand is required";
  // A truncated MERL file: one line naming the file, exit 2.
  const auto bad = std::filesystem::temp_directory_path() / ("svbrdf_cli_trunc_" + std::to_string(::getpid()) + ".binary");
  {
    std::ifstream good(gltf_merl_path(), std::ios::binary);
    std::vector<char> head(4096);
    good.read(head.data(), static_cast<std::streamsize>(head.size()));
    std::ofstream(bad, std::ios::binary).write(head.data(), static_cast<std::streamsize>(head.size()));
  }
  const CliRun trunc = run("eval measured --param file=" + bad.string(), "0 0 1 0 0 1\n");
  EXPECT_EQ(trunc.status, 2);
  EXPECT_NE(trunc.err.find("truncated"), std::string::npos) << trunc.err;
  EXPECT_EQ(lines(trunc.err), 1);
  std::filesystem::remove(bad);
  EXPECT_EQ(run("eval measured --param file=" + gltf_merl_path(), "0 0 1 0 0 1\n").status, 0);
}

// A parse error is one line with the program's name, as every bad input is (CLI11 printed two lines
// without it); --help still prints the help and exits 0. Numbers are checked against their ranges.
TEST(Cli, ParseErrorsAndBoundsAreOneLineWithTheProgramsName) {
  for (const char* args : {"eval", "eval lambert --bogus", "sample lambert --wo 0,0,1 --count 1e10",
                           "sample lambert --wo 0,0,1 --seed -1", "albedo lambert --theta-o 91", "albedo lambert --theta-o 10 --strata 0",
                           "plot lambert --theta-i nan --out x.svg"}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("svbrdf-brdf: ", 0), 0u) << args << ": " << r.err;
  }
  const CliRun help = run("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.err, "");
}

}  // namespace
}  // namespace svbrdf::testing
