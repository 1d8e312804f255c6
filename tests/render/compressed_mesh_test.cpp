// Compressed geometry read back: sample models compressed at test time by two tools that are not
// ours — gltf-pipeline (KHR_draco_mesh_compression) and glTF Transform (EXT_meshopt_compression),
// both from npm, installed by tools/install-deps into tools/node_modules — must load as the
// original does, within the precision the compressor was asked to keep, and render as it does.
// Broken compressed data must be refused the way every bad input is: one line naming the file and
// the glTF JSON path, exit 2, never a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "gltf/scene_reader.h"
#include "gltf_samples.h"
#include "gltf_test_files.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "textures/image.h"
#include "render_program.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

// The quantization both compressors are asked for (and what the tolerances below derive from).
constexpr int kPositionBits = 14, kNormalBits = 10, kTexcoordBits = 12, kColorBits = 8, kGenericBits = 12;

enum class Tool { draco, meshopt };

fs::path node_tool(const char* name) { return fs::path(SVBRDF_SOURCE_DIR) / "tools/node_modules/.bin" / name; }

// Compresses `in` into `out` (.glb) with the tool; false with the reason in `why` when it could not.
bool compress(Tool tool, const fs::path& in, const fs::path& out, std::string& why) {
  const fs::path exe = node_tool(tool == Tool::draco ? "gltf-pipeline" : "gltf-transform");
  if (!fs::exists(exe)) {
    why = exe.string() + " is absent: run tools/install-deps (needs npm)";
    return false;
  }
  std::string cmd;
  if (tool == Tool::draco)
    cmd = "'" + exe.string() + "' -i '" + in.string() + "' -o '" + out.string() +
          "' --draco.compressionLevel 7 --draco.quantizePositionBits " + std::to_string(kPositionBits) +
          " --draco.quantizeNormalBits " + std::to_string(kNormalBits) + " --draco.quantizeTexcoordBits " +
          std::to_string(kTexcoordBits) + " --draco.quantizeColorBits " + std::to_string(kColorBits) +
          " --draco.quantizeGenericBits " + std::to_string(kGenericBits);
  else
    cmd = "'" + exe.string() + "' meshopt '" + in.string() + "' '" + out.string() + "' --quantize-position " +
          std::to_string(kPositionBits) + " --quantize-normal " + std::to_string(kNormalBits) +
          " --quantize-texcoord " + std::to_string(kTexcoordBits) + " --quantize-color " + std::to_string(kColorBits);
  const fs::path log = out.parent_path() / "tool.log";
  if (std::system((cmd + " > '" + log.string() + "' 2>&1").c_str()) != 0 || !fs::exists(out)) {
    std::ifstream f(log);
    std::stringstream s;
    s << f.rdbuf();
    ADD_FAILURE() << cmd << " failed:\n" << s.str();
    why = "the compressor failed";
    return false;
  }
  return true;
}

// How far a decoded value may lie from the original, from the bits each tool was given.
struct Tolerance {
  double position = 0, normal_angle = 0, tangent_angle = 0, texcoord = 0, color = 0;
};

// An octahedral unit-vector code with each of its two coordinates rounded by at most `half_step`
// (on the [−1, 1] square): the unnormalized vector (u, v, 1 − |u| − |v|) moves by at most √6·half_step
// and is at least 1/√3 long, so the direction turns by at most √18·half_step radians.
double octahedral_angle(double half_step) { return std::sqrt(18.0) * half_step; }

// `extent` is the original model's largest bounding-box side (world space), `uv_range` and
// `color_range` the largest extents of its texture coordinates and colors.
Tolerance tolerance_for(Tool tool, double extent, double uv_range, double color_range) {
  Tolerance t;
  // Both tools put positions on a grid of 2^bits − 1 (Draco) or 2^bits − 2 (glTF Transform's signed
  // normalized) steps over the largest extent and round to it: half a step of error. One whole step
  // is allowed, the other half for float arithmetic and the node transform glTF Transform adds.
  t.position = extent / (std::ldexp(1.0, kPositionBits) - 2);
  t.texcoord = std::max(uv_range, 1.0) / (std::ldexp(1.0, kTexcoordBits) - 2);
  t.color = std::max(color_range, 1.0) / (std::ldexp(1.0, kColorBits) - 2);
  if (tool == Tool::draco) {
    // Draco's octahedral normals: [−1, 1] on 2^bits − 2 steps (its max_value), half a step of rounding.
    t.normal_angle = octahedral_angle(1.0 / (std::ldexp(1.0, kNormalBits) - 2));
    // Tangents are generic attributes to gltf-pipeline: each component on 2^bits − 1 steps over its
    // range (at most 2), half a step each; the xyz direction turns by at most √3 of that.
    t.tangent_angle = std::sqrt(3.0) * 1.0 / (std::ldexp(1.0, kGenericBits) - 2) + 1e-6;
  } else {
    // glTF Transform quantizes normals and tangents (to at least 8 bits a component), then encodes
    // them with the meshopt OCTAHEDRAL filter in bytes whatever --quantize-normal says above 8: three
    // roundings, each component by at most half of 1/127 — the quantized vector and the decoded one
    // (√3 of it in angle each), and the octahedral code between them.
    const double half = 0.5 / 127.0;
    t.normal_angle = t.tangent_angle = octahedral_angle(half) + 2 * std::sqrt(3.0) * half;
  }
  return t;
}

// A vertex in world space with every attribute the renderer reads.
struct WorldVertex {
  glm::dvec3 p{0}, n{0}, t{0};
  double w = 0;  // bitangent sign
  glm::dvec2 uv[2]{glm::dvec2(0), glm::dvec2(0)};
  glm::dvec4 c{1};
};

struct WorldMesh {
  std::vector<WorldVertex> vertices;
  std::size_t triangles = 0;
  glm::dvec3 lo{1e300}, hi{-1e300};
  glm::dvec2 uv_lo{1e300}, uv_hi{-1e300};
  double c_lo = 1e300, c_hi = -1e300;
};

WorldMesh world_mesh(const Scene& s) {
  WorldMesh m;
  for (const Instance& inst : s.instances) {
    const glm::dmat3 linear(inst.to_world);
    const glm::dmat3 normal = glm::transpose(glm::inverse(linear));
    for (const MeshPrimitive& p : s.meshes[std::size_t(inst.mesh)].primitives) {
      m.triangles += p.triangle_count();
      for (std::size_t i = 0; i < p.positions.size(); ++i) {
        WorldVertex v;
        v.p = glm::dvec3(inst.to_world * glm::dvec4(glm::dvec3(p.positions[i]), 1.0));
        v.n = glm::normalize(normal * glm::dvec3(p.normals[i]));
        if (!p.tangents.empty()) {
          v.t = glm::normalize(linear * glm::dvec3(p.tangents[i]));
          v.w = p.tangents[i].w;
        }
        for (int s2 = 0; s2 < 2; ++s2)
          if (!p.texcoords[s2].empty()) {
            v.uv[s2] = p.texcoords[s2][i];
            m.uv_lo = glm::min(m.uv_lo, v.uv[s2]), m.uv_hi = glm::max(m.uv_hi, v.uv[s2]);
          }
        if (!p.colors.empty()) {
          v.c = p.colors[i];
          for (int k = 0; k < 4; ++k) m.c_lo = std::min(m.c_lo, v.c[k]), m.c_hi = std::max(m.c_hi, v.c[k]);
        }
        m.lo = glm::min(m.lo, v.p), m.hi = glm::max(m.hi, v.p);
        m.vertices.push_back(v);
      }
    }
  }
  return m;
}

double angle(const glm::dvec3& a, const glm::dvec3& b) { return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)); }
double max_abs(const glm::dvec2& d) { return std::max(std::abs(d.x), std::abs(d.y)); }
double max_abs(const glm::dvec3& d) { return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}); }
double max_abs(const glm::dvec4& d) { return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z), std::abs(d.w)}); }

// The largest error of each attribute over the matched pairs, and how many vertices found no match.
struct MatchReport {
  std::size_t unmatched = 0;
  std::string first_unmatched;
  double position = 0, normal = 0, tangent = 0, texcoord = 0, color = 0;
};

// Every vertex of `a` must have a vertex of `b` within `tol` in every attribute. The compressors
// reorder vertices (and glTF Transform may split them), so vertices are matched by position first: a
// grid of cells one position tolerance wide, and the 27 cells around each vertex searched.
MatchReport match(const WorldMesh& a, const WorldMesh& b, const Tolerance& tol) {
  auto cell = [&](const glm::dvec3& p) { return glm::i64vec3(glm::floor(p / tol.position)); };
  auto key = [](const glm::i64vec3& c) { return std::uint64_t(c.x * 73856093) ^ std::uint64_t(c.y * 19349663) ^ std::uint64_t(c.z * 83492791); };
  std::unordered_multimap<std::uint64_t, std::size_t> grid;
  for (std::size_t i = 0; i < b.vertices.size(); ++i) grid.emplace(key(cell(b.vertices[i].p)), i);
  MatchReport r;
  for (const WorldVertex& v : a.vertices) {
    const glm::i64vec3 c = cell(v.p);
    const WorldVertex* best = nullptr;
    double best_score = 2;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto range = grid.equal_range(key(c + glm::i64vec3(dx, dy, dz)));
          for (auto it = range.first; it != range.second; ++it) {
            const WorldVertex& o = b.vertices[it->second];
            if (glm::length(v.t) > 0 && v.w != o.w) continue;
            // The worst attribute relative to its tolerance: 1 or less is a match, the least is kept.
            const double score = std::max({max_abs(v.p - o.p) / tol.position, angle(v.n, o.n) / tol.normal_angle,
                                           glm::length(v.t) > 0 ? angle(v.t, o.t) / tol.tangent_angle : 0.0,
                                           max_abs(v.uv[0] - o.uv[0]) / tol.texcoord,
                                           max_abs(v.uv[1] - o.uv[1]) / tol.texcoord, max_abs(v.c - o.c) / tol.color});
            if (score <= 1 && score < best_score) best = &o, best_score = score;
          }
        }
    if (!best) {
      if (r.unmatched++ == 0) {
        std::ostringstream s;
        s << "(" << v.p.x << ", " << v.p.y << ", " << v.p.z << ")";
        r.first_unmatched = s.str();
      }
      continue;
    }
    r.position = std::max(r.position, max_abs(v.p - best->p));
    r.normal = std::max(r.normal, angle(v.n, best->n));
    if (glm::length(v.t) > 0) r.tangent = std::max(r.tangent, angle(v.t, best->t));
    r.texcoord = std::max({r.texcoord, max_abs(v.uv[0] - best->uv[0]), max_abs(v.uv[1] - best->uv[1])});
    r.color = std::max(r.color, max_abs(v.c - best->c));
  }
  return r;
}

struct Case {
  const char* model;  // under gltf-samples: MODEL/glTF/MODEL.gltf
  Tool tool;
};

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  return std::string(info.param.model) + (info.param.tool == Tool::draco ? "Draco" : "Meshopt");
}

fs::path sample(const char* model) { return test::samples_dir() / model / "glTF" / (std::string(model) + ".gltf"); }

// ---- the decoded geometry against the original ---------------------------------------------------

class CompressedMesh : public ::testing::TestWithParam<Case> {};

// Suzanne: POSITION, NORMAL, TANGENT, TEXCOORD_0 and indices; MultiUVTest adds TEXCOORD_1;
// VertexColorTest adds COLOR_0.
TEST_P(CompressedMesh, MatchesTheOriginalWithinItsQuantization) {
  const Case& c = GetParam();
  if (!fs::exists(test::samples_dir())) GTEST_SKIP() << "no glTF samples at " << test::samples_dir() << " (../shared absent)";
  test::TempDir dir;
  const fs::path out = dir.path() / "compressed.glb";
  std::string why;
  if (!compress(c.tool, sample(c.model), out, why)) GTEST_SKIP() << why;
  const Scene original = load_gltf(sample(c.model)), decoded = load_gltf(out);
  const WorldMesh a = world_mesh(original), b = world_mesh(decoded);
  EXPECT_EQ(b.triangles, a.triangles);
  const glm::dvec3 extent = a.hi - a.lo;
  const glm::dvec2 uv = a.uv_hi - a.uv_lo;
  const Tolerance tol = tolerance_for(c.tool, std::max({extent.x, extent.y, extent.z}), std::max({uv.x, uv.y, 0.0}),
                                      std::max(a.c_hi - a.c_lo, 0.0));
  const MatchReport forward = match(b, a, tol), backward = match(a, b, tol);
  EXPECT_EQ(forward.unmatched, 0u) << "of " << b.vertices.size() << " decoded vertices, first at " << forward.first_unmatched;
  EXPECT_EQ(backward.unmatched, 0u) << "of " << a.vertices.size() << " original vertices, first at " << backward.first_unmatched;
  std::printf("%s: %zu -> %zu vertices; max error / tolerance: position %.3g / %.3g, normal %.3g / %.3g rad, "
              "tangent %.3g / %.3g rad, texcoord %.3g / %.3g, color %.3g / %.3g\n",
              case_name({c, 0}).c_str(), a.vertices.size(), b.vertices.size(), forward.position, tol.position,
              forward.normal, tol.normal_angle, forward.tangent, tol.tangent_angle, forward.texcoord, tol.texcoord,
              forward.color, tol.color);
}

INSTANTIATE_TEST_SUITE_P(Samples, CompressedMesh,
                         ::testing::Values(Case{"Suzanne", Tool::draco}, Case{"Suzanne", Tool::meshopt},
                                           Case{"MultiUVTest", Tool::draco}, Case{"MultiUVTest", Tool::meshopt},
                                           Case{"VertexColorTest", Tool::draco},
                                           Case{"VertexColorTest", Tool::meshopt}),
                         case_name);

// ---- a render of each ----------------------------------------------------------------------------

// An environment whose radiance is linear in the direction's polar cosine, L = 1 + cos θ / 2: every
// radiance in [1/2, 3/2], changing by at most 1/2 per radian of direction. A surface's reflected
// radiance averages L over directions tied to its normal; turning the normal by δ turns those by at
// most 2δ, which changes it by at most δ, under 2δ of itself. (Under a uniform sky a diffuse surface
// looks the same whatever its normal; under a sun a glossy highlight moves by whole pixels.)
fs::path gradient_sky(const fs::path& dir) {
  Image sky(32, 16, 3);
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < sky.width; ++x)
      for (int c = 0; c < 3; ++c) sky.at(x, y, c) = float(1 + 0.5 * std::cos(M_PI * (y + 0.5) / sky.height));
  const fs::path f = dir / "sky.exr";
  write_image(f, sky, PixelFormat::float32);
  return f;
}

Film render_small(const fs::path& file, const fs::path& sky) {
  SceneSetup setup;
  setup.width = setup.height = 64;
  setup.env = sky.string();
  const PreparedScene prepared(load_gltf(file), setup);
  RenderOptions o;
  o.spp = 16;
  o.seed = 7;
  o.threads = 2;
  o.integrator.max_depth = 4;
  o.integrator.filter = TextureFilter::param;
  return render(prepared.world(), o, nullptr);
}

class CompressedRender : public ::testing::TestWithParam<Tool> {};

// Suzanne at 64², 16 samples per pixel, the same seed, under gradient_sky. The geometry moves by
// under 1/16000 of the model (a hundredth of a pixel here), and each normal turns by at most the
// tolerance's angle δ (0.0042 rad for Draco's 10 bits, 0.030 for glTF Transform's bytes), which
// changes each pixel by under 2δ of itself: the mean absolute difference over the model's pixels
// may be 2δ of their mean.
TEST_P(CompressedRender, AgreesWithTheOriginal) {
  if (!fs::exists(test::samples_dir())) GTEST_SKIP() << "no glTF samples at " << test::samples_dir() << " (../shared absent)";
  test::TempDir dir;
  const fs::path out = dir.path() / "compressed.glb";
  std::string why;
  if (!compress(GetParam(), sample("Suzanne"), out, why)) GTEST_SKIP() << why;
  const fs::path sky = gradient_sky(dir.path());
  const Film fa = render_small(sample("Suzanne"), sky), fb = render_small(out, sky);
  const Image a = fa.radiance(), b = fb.radiance(), depth = fa.depth();
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  // Over the model's pixels (a first hit at some depth): the sky around it is the same in both.
  double diff = 0, sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    if (std::isfinite(depth.pixels[i / 3]) && depth.pixels[i / 3] > 0)
      diff += std::abs(double(a.pixels[i]) - b.pixels[i]), sum += a.pixels[i];
  ASSERT_GT(sum, 0.0);
  const double relative = diff / sum, allowed = 2 * tolerance_for(GetParam(), 1, 1, 1).normal_angle;
  std::printf("Suzanne %s: mean |difference| / mean = %.5f, allowed %.4f\n",
              GetParam() == Tool::draco ? "Draco" : "meshopt", relative, allowed);
  EXPECT_LT(relative, allowed);
}

INSTANTIATE_TEST_SUITE_P(Suzanne, CompressedRender, ::testing::Values(Tool::draco, Tool::meshopt),
                         [](const ::testing::TestParamInfo<Tool>& info) {
                           return std::string(info.param == Tool::draco ? "Draco" : "Meshopt");
                         });

// ---- broken compressed data ----------------------------------------------------------------------

struct Glb {
  nlohmann::json json;
  std::vector<unsigned char> bin;
};

Glb read_glb(const fs::path& file) {
  std::ifstream f(file, std::ios::binary);
  const std::vector<unsigned char> b((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  auto u32 = [&](std::size_t at) { return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 | std::uint32_t(b[at + 3]) << 24; };
  Glb g;
  const std::uint32_t json_length = u32(12);
  g.json = nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + json_length);
  const std::size_t bin_at = 20 + json_length;
  g.bin.assign(b.begin() + std::ptrdiff_t(bin_at + 8), b.begin() + std::ptrdiff_t(bin_at + 8 + u32(bin_at)));
  return g;
}

// BoxTextured compressed by `tool`, as JSON and binary chunk, or a skip reason.
bool compressed_box(Tool tool, const test::TempDir& dir, Glb& out, std::string& why) {
  if (!fs::exists(test::samples_dir())) {
    why = "no glTF samples at " + test::samples_dir().string() + " (../shared absent)";
    return false;
  }
  const fs::path glb = dir.path() / "box.glb";
  if (!compress(tool, sample("BoxTextured"), glb, why)) return false;
  out = read_glb(glb);
  return true;
}

// svbrdf-render on `file`, tiny.
test::RenderRun render_tiny(const fs::path& file, const test::TempDir& dir) {
  const std::vector<std::string> args = {test::kRenderProgram, file.string(), "--res", "8x6", "--spp", "1", "-q",
                                         "-o", (dir.path() / "o.exr").string()};
  return test::run_to_end(args, dir.path());
}

// svbrdf-render must end with exit 2 and one line that names `expect`, never a signal.
void expect_refused(const Glb& g, const test::TempDir& dir, const std::string& expect) {
  const fs::path file = dir.write_bytes("broken.glb", test::make_glb(g.json.dump(), g.bin));
  const test::RenderRun r = render_tiny(file, dir);
  ASSERT_TRUE(r.end.exited) << "signal " << r.end.signal << (r.end.timed_out ? " (timed out)" : "") << ": " << r.err;
  EXPECT_EQ(r.end.code, 2) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("broken.glb: " + expect), std::string::npos) << "expected '" << expect << "' in: " << r.err;
}

// BoxTextured compressed by tool T, read into `g`; the test is skipped when it cannot be.
template <Tool T>
class CompressedBox : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!compressed_box(T, dir, g, why)) GTEST_SKIP() << why;
  }
  const nlohmann::json& draco_extension() const {
    return g.json["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"];
  }
  // The first buffer view with EXT_meshopt_compression.
  std::size_t meshopt_view() const {
    std::size_t view = 0;
    while (!g.json["bufferViews"][view].contains("extensions")) ++view;
    return view;
  }
  test::TempDir dir;
  Glb g;
};
using DracoInput = CompressedBox<Tool::draco>;
using MeshoptInput = CompressedBox<Tool::meshopt>;

TEST_F(DracoInput, TruncatedDataIsRefused) {
  const int view = draco_extension()["bufferView"].get<int>();
  auto& length = g.json["bufferViews"][std::size_t(view)]["byteLength"];
  length = length.get<std::uint64_t>() / 2;
  expect_refused(g, dir, "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.bufferView: ");
}

TEST_F(DracoInput, PointCountDisagreeingWithTheAccessorIsRefused) {
  const int position = g.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>();
  auto& count = g.json["accessors"][std::size_t(position)]["count"];
  count = count.get<std::uint64_t>() + 1;
  expect_refused(g, dir, "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression.attributes.POSITION: decodes to");
}

// Bytes of the Draco stream overwritten, past its header, in 16 files: each either loads (the
// damage fell on values, which are then only wrong) or is refused with one line naming the
// extension; never a signal or a hang. The sanitizer run (make asan) watches the reads.
TEST_F(DracoInput, CorruptedDataNeverCrashes) {
  const auto& view = g.json["bufferViews"][draco_extension()["bufferView"].get<std::size_t>()];
  const std::size_t at = view.value("byteOffset", std::size_t(0)), length = view["byteLength"].get<std::size_t>();
  std::uint32_t state = 12345;
  int refused = 0;
  for (int k = 0; k < 16; ++k) {
    Glb broken = g;
    for (int j = 0; j < 4; ++j) {
      state = state * 1664525u + 1013904223u;
      broken.bin[at + 16 + state % (length - 16)] ^= static_cast<unsigned char>(1 + (state >> 24) % 255);
    }
    const fs::path file = dir.write_bytes("corrupt.glb", test::make_glb(broken.json.dump(), broken.bin));
    const test::RenderRun r = render_tiny(file, dir);
    ASSERT_TRUE(r.end.exited) << "case " << k << ": signal " << r.end.signal << ": " << r.err;
    if (r.end.code == 0) continue;
    ++refused;
    EXPECT_EQ(r.end.code, 2) << "case " << k << ": " << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << "case " << k << ": " << r.err;
    EXPECT_NE(r.err.find("KHR_draco_mesh_compression"), std::string::npos) << "case " << k << ": " << r.err;
  }
  std::printf("%d of 16 corrupted files refused, the others loaded\n", refused);
}

TEST_F(MeshoptInput, TruncatedDataIsRefused) {
  const std::size_t view = meshopt_view();
  auto& length = g.json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["byteLength"];
  length = length.get<std::uint64_t>() / 2;
  expect_refused(g, dir, "bufferViews[" + std::to_string(view) + "].extensions.EXT_meshopt_compression: ");
}

// EXT_meshopt_compression README, "Fallback buffers": a fallback buffer's bytes exist only as the
// views decoded into it, so a view that reads it uncompressed reads nothing the file holds.
TEST_F(MeshoptInput, UncompressedViewOfAFallbackBufferIsRefused) {
  const std::size_t view = meshopt_view();
  g.json["bufferViews"][view].erase("extensions");
  expect_refused(g, dir, "bufferViews[" + std::to_string(view) + "].buffer: ");
}

}  // namespace
}  // namespace svbrdf
