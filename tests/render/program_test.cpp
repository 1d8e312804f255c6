// svbrdf-render as a program: exit codes, one-line errors, the EXR it writes (signals: interrupt_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <sys/wait.h>

#include "base/message_line.h"
#include "gltf_test_files.h"
#include "textures/image.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

const std::string kProgram = std::string(SVBRDF_BINARY_DIR) + "/svbrdf-render";

struct RunResult {
  int code = -1;
  std::string err;
};

RunResult run_program(const std::string& args, const test::TempDir& dir) {
  const fs::path err = dir.path() / "stderr.txt";
  const std::string cmd = "'" + kProgram + "' " + args + " 2> '" + err.string() + "' > /dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::ifstream in(err);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  return r;
}

TEST(Program, MalformedGltfIsOneLineAndExit2) {
  test::TempDir dir;
  test::GltfQuad q;
  q.indices = {0, 1, 2, 0, 2, 7};
  const fs::path f = dir.write("bad.gltf", q.json());
  const RunResult r = run_program("'" + f.string() + "' -q -o '" + (dir.path() / "o.exr").string() + "'", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("meshes[0].primitives[0].indices"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "o.exr")) << "nothing written for bad input";
}

// A corrupt file's bytes that the JSON parser quotes in its message reach the terminal as text:
// the line stays one line of well-formed UTF-8 (base/message_line.h).
TEST(Program, CorruptBytesInTheMessageAreEscaped) {
  test::TempDir dir;
  const fs::path f = dir.write("corrupt.gltf", std::string("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [\xFF\x01\x80]}"));
  const RunResult r = run_program("'" + f.string() + "' -q -o '" + (dir.path() / "o.exr").string() + "'", dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (std::size_t i = 0; i + 1 < r.err.size();) {  // all but the line's own '\n'
    const std::size_t n = kept_length(r.err, i);
    ASSERT_GT(n, 0u) << "byte " << i << " (" << int(static_cast<unsigned char>(r.err[i])) << ") of: " << r.err;
    i += n;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "o.exr"));
}

TEST(Program, BadArgumentsExit2) {
  test::TempDir dir;
  const fs::path f = dir.write("q.gltf", test::GltfQuad().json());
  const std::string base = "'" + f.string() + "' -q -o '" + (dir.path() / "o.exr").string() + "' ";
  EXPECT_EQ(run_program(base + "--res 12by3", dir).code, 2);
  EXPECT_EQ(run_program(base + "--camera 3", dir).code, 2);
  EXPECT_EQ(run_program(base + "--env nowhere.exr", dir).code, 2);
  const RunResult p = run_program(base + "--filter trilinear", dir);
  EXPECT_EQ(p.code, 2);
  EXPECT_NE(p.err.find("--filter"), std::string::npos) << p.err;
  EXPECT_EQ(run_program("'" + (dir.path() / "none.gltf").string() + "' -q", dir).code, 2);
  // A number out of range is named with what it must be, in one short line (CLI11's own check
  // printed the largest double in full: base/cli_checks.h).
  for (const char* arg : {"--spp 0", "--spp x", "--threads -1", "--footprint-scale 0", "--footprint-scale inf"}) {
    const RunResult n = run_program(base + arg, dir);
    EXPECT_EQ(n.code, 2) << arg;
    const std::string option = std::string(arg).substr(0, std::string(arg).find(' '));
    EXPECT_NE(n.err.find(option + ": must be a "), std::string::npos) << arg << ": " << n.err;
    EXPECT_LT(n.err.size(), 200u) << arg << ": " << n.err;
  }
}

// A Lambertian square of side 8 at z = 0 facing +z, of albedo `rgb` (glTF's specular layer off
// through KHR_materials_specular), as the light-unit tests below see it.
test::GltfQuad lambertian_quad(const std::string& rgb) {
  test::GltfQuad q;
  q.positions = {-4, -4, 0, 4, -4, 0, 4, 4, 0, -4, 4, 0};
  q.materials = R"([{"pbrMetallicRoughness": {"baseColorFactor": [)" + rgb + R"(, 1], "metallicFactor": 0},
                     "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}])";
  q.primitive_extra = R"(, "material": 0)";
  return q;
}

// End to end through the file format: a Lambertian quad (glTF's specular layer off through
// KHR_materials_specular) under a KHR_lights_punctual directional light of E lux at 60°, an
// orthographic glTF camera, a black environment: every pixel of the float EXR is ρ/π·(E/683)·cos 60°,
// the extension's lux turned into W/m² with 683 lm/W. The same file with its intensity written in
// W/m² and --light-units radiometric gives the same image.
TEST(Program, UnitsEndToEnd) {
  test::TempDir dir;
  test::GltfQuad q = lambertian_quad("0.25, 0.5, 0.75");
  // Light node: rotated so its −Z travels along −(sin 60°, 0, cos 60°): a rotation of 60° about +Y.
  q.nodes = R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]},
                {"rotation": [0, 0.5, 0, 0.8660254037844387], "extensions": {"KHR_lights_punctual": {"light": 0}}}])";
  q.scene_nodes = "[0, 1, 2]";
  const std::string camera = R"(, "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.01, "zfar": 10}}],
    "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_specular"],)";
  const float lux = 1707.5f, watts = 2.5f;  // 2.5 W/m² × 683 lm/W
  q.top_extra = camera + R"("extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 1707.5}]}})";
  const fs::path f = dir.write("lit.gltf", q.json());
  const fs::path out = dir.path() / "lit.exr";
  const RunResult r = run_program("'" + f.string() + "' -q --float --env 0,0,0 --res 8x8 --spp 2 -o '" + out.string() + "'", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir.path() / "lit.png"));
  const Image im = read_image(out);
  ASSERT_EQ(im.width, 8);
  const float rho[3] = {0.25f, 0.5f, 0.75f};
  // The PNG is the same radiance through the display transform: sRGB's IEC 61966-2-1 encoding
  // (exposure 0), in 8 bits.
  const Image png = read_image(dir.path() / "lit.png");
  for (int c = 0; c < 3; ++c) {
    const float expected = rho[c] / 3.14159265f * (lux / 683.0f) * 0.5f;
    EXPECT_NEAR(im.at(3, 4, c), expected, 2e-6f * expected);
    const float encoded = expected <= 0.0031308f ? 12.92f * expected : 1.055f * std::pow(expected, 1.0f / 2.4f) - 0.055f;
    EXPECT_NEAR(png.at(3, 4, c), encoded, 0.6f / 255.0f);
  }

  q.top_extra = camera + R"("extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 2.5}]}})";
  const fs::path g = dir.write("radiometric.gltf", q.json());
  const fs::path out2 = dir.path() / "radiometric.exr";
  const RunResult r2 = run_program("'" + g.string() + "' -q --float --env 0,0,0 --res 8x8 --spp 2 --light-units radiometric -o '" +
                                       out2.string() + "'", dir);
  ASSERT_EQ(r2.code, 0) << r2.err;
  const Image im2 = read_image(out2);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(im2.at(3, 4, c), rho[c] / 3.14159265f * watts * 0.5f, 2e-6f * watts);
}

// A point light and a spot light of I candela at height d above a Lambertian quad, seen by an
// orthographic camera: the irradiance at distance r from the foot of the light is
// (I/683)·cosθ/(r² + d²) = (I/683)·d/(r² + d²)^{3/2} W/m² (the inverse-square law, candela turned into
// W/sr by 683 lm/W), times the spot's falloff as KHR_lights_punctual writes it,
// saturate((cosθ − cos θ_outer)/(cos θ_inner − cos θ_outer))². A pixel's value is the mean of that
// radiance over the pixel (a box filter), so it lies between the closed form's minimum and maximum
// over the pixel, found here on a fine grid of it.
TEST(Program, PointAndSpotLightsInCandela) {
  test::TempDir dir;
  test::GltfQuad q = lambertian_quad("0.5, 0.5, 0.5");
  const double d = 1.0, I = 1366.0, rho = 0.5;  // 2 W/sr
  const double outer = 0.5235987755982988, inner = 0.2617993877991494;  // 30° and 15°
  // The light's −Z points down at the quad as placed: no rotation needed.
  q.nodes = R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]},
                {"translation": [0, 0, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}}])";
  q.scene_nodes = "[0, 1, 2]";
  const int n = 32;
  for (const bool spot : {false, true}) {
    SCOPED_TRACE(spot ? "spot" : "point");
    const auto radiance = [&](double x, double y) {
      const double r2 = x * x + y * y + d * d, cos_theta = d / std::sqrt(r2);
      double falloff = 1.0;
      if (spot) {
        const double t = std::clamp((cos_theta - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0, 1.0);
        falloff = t * t;
      }
      return rho / 3.141592653589793 * (I / 683.0) * cos_theta / r2 * falloff;
    };
    const std::string light = spot ? R"({"type": "spot", "intensity": 1366, "spot": {"innerConeAngle": 0.2617993877991494,
                                          "outerConeAngle": 0.5235987755982988}})"
                                   : R"({"type": "point", "intensity": 1366})";
    q.top_extra = R"(, "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.01, "zfar": 10}}],
      "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_specular"],
      "extensions": {"KHR_lights_punctual": {"lights": [)" + light + "]}}";
    const fs::path f = dir.write("p.gltf", q.json());
    const fs::path out = dir.path() / "p.exr";
    const RunResult r = run_program("'" + f.string() + "' -q --float --env 0,0,0 --res " + std::to_string(n) + "x" +
                                        std::to_string(n) + " --spp 4 -o '" + out.string() + "'", dir);
    ASSERT_EQ(r.code, 0) << r.err;
    const Image im = read_image(out);
    ASSERT_EQ(im.width, n);
    int dark = 0, band = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        // The pixel's extent on the quad: [−1, 1]² split n ways (symmetric about the light's foot,
        // so the image's orientation does not matter).
        const double x0 = -1.0 + 2.0 * i / n, y0 = -1.0 + 2.0 * j / n, w = 2.0 / n;
        double lo = 1e30, hi = 0.0;
        for (int a = 0; a <= 16; ++a)
          for (int b = 0; b <= 16; ++b) {
            const double v = radiance(x0 + w * a / 16.0, y0 + w * b / 16.0);
            lo = std::min(lo, v), hi = std::max(hi, v);
          }
        const float v = im.at(i, j, 1);
        EXPECT_GE(v, lo * (1.0 - 1e-3) - 1e-7) << i << "," << j;
        EXPECT_LE(v, hi * (1.0 + 1e-3) + 1e-7) << i << "," << j;
        dark += hi == 0.0;
        // Pixels in the cone's smooth edge: the falloff at the centre well inside (0, 1).
        const double cx = x0 + w / 2, cy = y0 + w / 2;
        const double t = (d / std::sqrt(cx * cx + cy * cy + d * d) - std::cos(outer)) / (std::cos(inner) - std::cos(outer));
        band += t > 0.1 && t < 0.9;
      }
    if (spot) {
      EXPECT_GT(dark, 200);  // the cone's outside is black
      EXPECT_GT(band, 20);   // and its smooth edge was tested
    }
  }
}

}  // namespace
}  // namespace svbrdf
