// A user's program against the installed package: every public header (docs/library.md) in one
// translation unit, a BSDF model by name, a MIP pyramid built from a generated texture set, and a
// symbol of the renderer, each checked against what it must be whatever the code computing it.
#include <svbrdf/appearance/albedo.h>
#include <svbrdf/appearance/blinn_phong.h>
#include <svbrdf/appearance/bsdf.h>
#include <svbrdf/appearance/conductor_mirror.h>
#include <svbrdf/appearance/cook_torrance.h>
#include <svbrdf/appearance/dielectric.h>
#include <svbrdf/appearance/eon.h>
#include <svbrdf/appearance/frame.h>
#include <svbrdf/appearance/fresnel.h>
#include <svbrdf/appearance/gltf.h>
#include <svbrdf/appearance/gltf_bsdf.h>
#include <svbrdf/appearance/gltf_surface_bsdf.h>
#include <svbrdf/appearance/lafortune.h>
#include <svbrdf/appearance/lambert.h>
#include <svbrdf/appearance/measured.h>
#include <svbrdf/appearance/microfacet.h>
#include <svbrdf/appearance/microfacet_normal_mapping.h>
#include <svbrdf/appearance/mirror.h>
#include <svbrdf/appearance/mixture.h>
#include <svbrdf/appearance/oren_nayar.h>
#include <svbrdf/appearance/phong.h>
#include <svbrdf/appearance/registry.h>
#include <svbrdf/appearance/sheen.h>
#include <svbrdf/appearance/thin_film.h>
#include <svbrdf/base/error.h>
#include <svbrdf/base/math.h>
#include <svbrdf/gltf/scene.h>
#include <svbrdf/gltf/scene_reader.h>
#include <svbrdf/mip/gltf_material.h>
#include <svbrdf/mip/metrics.h>
#include <svbrdf/mip/mip.h>
#include <svbrdf/mip/mip_file.h>
#include <svbrdf/mip/texture_filter.h>
#include <svbrdf/render/mip_cache.h>
#include <svbrdf/render/output.h>
#include <svbrdf/render/render_setup.h>
#include <svbrdf/render/renderer.h>
#include <svbrdf/textures/color.h>
#include <svbrdf/textures/image.h>
#include <svbrdf/textures/material_family.h>
#include <svbrdf/textures/material_loader.h>
#include <svbrdf/textures/material_texels.h>
#include <svbrdf/textures/sampler.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace {

int failures = 0;

void expect_near(const char* what, float got, float want, float relative) {
  if (std::fabs(got - want) <= relative * std::fabs(want)) return;
  std::printf("FAIL %s: %.9g, expected %.9g\n", what, got, want);
  ++failures;
}

void expect_near(const char* what, const glm::vec3& got, const glm::vec3& want, float relative) {
  for (int c = 0; c < 3; ++c) expect_near(what, got[c], want[c], relative);
}

}  // namespace

int main() {
  // Lambert by name (CGPP §27.7.1): f = albedo/π for every pair of directions above the surface.
  const svbrdf::Rgb albedo(0.2f, 0.4f, 0.6f);
  const auto lambert = svbrdf::make_model("lambert", {"albedo=0.2,0.4,0.6"});
  const glm::vec3 directions[] = {glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f)), glm::vec3(0, 0, 1),
                                  glm::normalize(glm::vec3(-0.7f, 0.1f, 0.2f))};
  for (const glm::vec3& wi : directions)
    for (const glm::vec3& wo : directions)
      expect_near("lambert eval", lambert->eval(wi, wo), albedo / std::numbers::pi_v<float>, 1e-6f);

  // A generated texture set, the same parameters at every texel: every level of its pyramids
  // averages equal texels, so the coarsest level holds the constant (the parameter pyramid) and a
  // BRDF equal to the level-0 one (the BRDF pyramid).
  svbrdf::MaterialTexels texels(16, 16);
  for (std::size_t k = 0; k < texels.size(); ++k) {
    texels.base_color[k] = glm::vec3(0.7f, 0.5f, 0.3f);
    texels.metallic[k] = 0.25f;
    texels.roughness[k] = 0.6f;
  }
  svbrdf::MipTexture mip(texels, svbrdf::WrapMode::repeat, svbrdf::WrapMode::repeat, svbrdf::TextureFilter::param);
  mip.prepare(svbrdf::TextureFilter::brdf);
  // A footprint the whole texture wide: the coarsest level, log2(16) = 4.
  const svbrdf::Footprint whole{{0.3f, 0.7f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
  expect_near("MIP level of a footprint the texture wide", mip.level(whole), 4.0f, 1e-6f);
  expect_near("coarsest base colour", mip.base_color(svbrdf::TextureFilter::param, whole),
              glm::vec3(0.7f, 0.5f, 0.3f), 1e-6f);
  svbrdf::LobeMixtureBsdf coarse, fine;
  mip.lookup(svbrdf::TextureFilter::brdf, whole, svbrdf::Rgb(1.0f), 0.5f, coarse);
  const svbrdf::Footprint point{{0.3f, 0.7f}, {0.0f, 0.0f}, {0.0f, 0.0f}};
  mip.lookup(svbrdf::TextureFilter::level0, point, svbrdf::Rgb(1.0f), 0.5f, fine);
  for (const glm::vec3& wi : directions)
    for (const glm::vec3& wo : directions)
      expect_near("coarsest BRDF against level 0", coarse.eval(wi, wo), fine.eval(wi, wo), 1e-3f);

  // The renderer's library links with its dependencies (Embree among them).
  const auto color = svbrdf::parse_color("0.25,0.5,1");
  if (!color || *color != svbrdf::Rgb(0.25f, 0.5f, 1.0f)) {
    std::printf("FAIL parse_color\n");
    ++failures;
  }

  if (failures == 0) std::printf("consumer: every check holds\n");
  return failures == 0 ? 0 : 1;
}
