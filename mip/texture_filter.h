#pragma once
// How a texture is filtered, and the footprint a filter reads at a hit: the one name for the ways
// ../shared/spec/brdf-mip.md compares and svbrdf-render renders with. svbrdf-render's --filter and
// svbrdf-bake's --mode take these names.
//
//   level0  — no MIP: the nearest level-0 texel at the exact uv (the ground truth at many samples
//             per pixel). It stores no coarse texel.
//   param   — the parameter pyramid (param_pyramid.h), what ordinary MIP mapping does;
//   toksvig, vmf — the same storage with an engine baseline's α widening;
//   brdf    — the BRDF pyramid (brdf_pyramid.h), the BRDF-averaged MIP texel.
//
// The spec's `exact` is not among them: it is the reference the filters are measured against, F of
// a coarse texel by brute force over the texels it covers (exact_reference.h), not a way to filter.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace svbrdf {

enum class TextureFilter { level0, param, toksvig, vmf, brdf };

// "level0", "param", "toksvig", "vmf", "brdf".
std::string_view filter_name(TextureFilter f);
std::optional<TextureFilter> parse_filter(std::string_view name);
// Every filter's name, in the enum's order.
std::vector<std::string> filter_names();

// Whether the filter reads the parameter pyramid (param and the engine baselines).
inline bool reads_param_pyramid(TextureFilter f) {
  return f == TextureFilter::param || f == TextureFilter::toksvig || f == TextureFilter::vmf;
}

// A texture coordinate and its footprint: the derivatives of uv along the pixel's two screen axes
// (from ray differentials).
struct Footprint {
  glm::vec2 uv{0.0f};
  glm::vec2 duv_dx{0.0f};  // d(uv)/d(screen x)
  glm::vec2 duv_dy{0.0f};  // d(uv)/d(screen y)
};

}  // namespace svbrdf
