// The glTF sample models render: no error, every pixel finite and non-negative, something visible.
// The fast suite renders a few small models small (SVBRDF_SAMPLE_RES², SVBRDF_SAMPLE_SPP); the
// `long` suite (SVBRDF_ALL_SAMPLES) renders every model at 256² and 16 samples per pixel with the
// default filter, the one a user gets.
#include <gtest/gtest.h>

#include <cmath>

#include "gltf_samples.h"
#include "gltf/scene_reader.h"
#include "render/render_setup.h"
#include "render/renderer.h"

#ifndef SVBRDF_SAMPLE_RES
#define SVBRDF_SAMPLE_RES 24
#endif
#ifndef SVBRDF_SAMPLE_SPP
#define SVBRDF_SAMPLE_SPP 1
#endif
// The fast suite filters with `param` (its pyramid builds in a fraction of a second even for 2048²
// textures; the BRDF pyramid of a normal-mapped 2048² material takes seconds on 2 cores, and
// mip_filter_test.cpp covers brdf); the long suite renders with the default, brdf.
#ifndef SVBRDF_SAMPLE_FILTER
#define SVBRDF_SAMPLE_FILTER TextureFilter::param
#endif

namespace svbrdf {
namespace {

class SampleRender : public ::testing::TestWithParam<test::SampleCounts> {};

TEST_P(SampleRender, RendersFinite) {
  const auto file = test::samples_dir() / GetParam().file;
  if (!std::filesystem::exists(test::samples_dir()))
    GTEST_SKIP() << "no glTF samples at " << test::samples_dir() << " (../shared absent)";
  SceneSetup setup;
  setup.width = setup.height = SVBRDF_SAMPLE_RES;
  const PreparedScene prepared(load_gltf(file), setup);
  RenderOptions o;
  o.spp = SVBRDF_SAMPLE_SPP;
  o.integrator.max_depth = 8;
  o.integrator.filter = SVBRDF_SAMPLE_FILTER;
  RenderStats stats;
  const Image im = render(prepared.world(), o, &stats).radiance();
  EXPECT_EQ(stats.samples, std::uint64_t(SVBRDF_SAMPLE_RES) * SVBRDF_SAMPLE_RES * SVBRDF_SAMPLE_SPP);
  double sum = 0.0;
  for (float v : im.pixels) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
    sum += v;
  }
  EXPECT_GT(sum, 0.0) << "an all-black image";
}

#ifdef SVBRDF_ALL_SAMPLES
const auto& kRendered = test::kSamples;
#else
// Instancing, mirroring transforms, alpha modes, texture transforms, vertex colors, glTF cameras,
// punctual lights and a .glb: one model each, small ones.
const test::SampleCounts kRendered[] = {test::kSamples[0], test::kSamples[2], test::kSamples[6], test::kSamples[9],
                                        test::kSamples[10], test::kSamples[15], test::kSamples[31], test::kSamples[34]};
#endif

INSTANTIATE_TEST_SUITE_P(Samples, SampleRender, ::testing::ValuesIn(kRendered),
                         [](const ::testing::TestParamInfo<test::SampleCounts>& info) {
                           std::string n = info.param.file;
                           return n.substr(0, n.find('/')) + (n.find(".glb") != std::string::npos ? "Glb" : "Gltf");
                         });

}  // namespace
}  // namespace svbrdf
