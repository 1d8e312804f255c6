#pragma once
// The one texel grid a material's textures are resampled onto before its MIP pyramid is built
// (render/material_mips.h): a BRDF-averaged texel needs every parameter of every point it covers,
// known together, so textures that a glTF material maps differently — another KHR_texture_transform
// (any invertible affine map), another size, another wrap mode — are first brought onto one grid.
//
// The grid follows one of the textures (its uv set, transform and wrap modes) over that texture's
// [0, 1]², and its texel (i, j) holds, of every texture, the texel the level0 lookup reads at the
// grid texel's centre t: the nearest texel at A_k(t), A_k = T_k ∘ T_grid⁻¹ the affine map from the
// grid's texture space to texture k's, under k's own wrap modes (textures/sampler.h).
//
// Which texture it follows, and its size, are chosen so that the grid answers for every texture
// wherever the surface looks it up:
//   - size: along each axis at least as many texels as any texture has across the grid's unit (so no
//     texel of any texture is skipped), then the smallest multiple (up to 4) at which every texture's
//     texel spans a whole number q of grid texels (A_k axis-aligned or turned by a quarter, its scale
//     making texels of q grid texels). Then each texture texel's value goes to exactly q² grid
//     texels, its share of any region of the grid its share of the surface. "Exact" when moreover its
//     edges fall on grid texel edges (its offset a whole number of grid texels): the grid reproduces
//     each texture's level0 lookup at every point. Otherwise ("displaced": an offset of a fraction of
//     a texel) each texture sits on the grid shifted by the same less than half a grid texel
//     everywhere, so a texel of level λ (2^λ grid texels a side) averages its texels over a window
//     shifted by at most 2^−(λ+1) of its side along each axis: at most 2^−λ of its area is another
//     texel's, and the renderer shades level-0 hits from the textures themselves (level0 lookups).
//     Texels of a fractional number of grid texels (a non-integer ratio of sizes or scales that no
//     multiple up to 4 resolves, or a rotation other than by quarter turns) would take uneven shares
//     of the grid — an error at every level, not only at edges — and are refused.
//   - wrap: inside the grid's [0, 1]² the grid is each texture's own value whatever the wrap modes.
//     Where the surface's uv (the vertices' bounding box on the grid's uv set) reach past [0, 1] along
//     an axis, the grid is read with its own wrap mode there, so each texture must continue as the
//     grid does: the grid repeats and A_k moves a whole number of k's periods per grid period (A_k's column
//     of that axis an integer vector), k repeating along each axis it moves (or mirroring, when it
//     moves an even number: mirrored repeat's period is 2); or the grid clamps or mirrors and A_k is
//     the identity on that axis with k's wrap mode the same. A footprint that reaches past the
//     surface's own uv range reads the grid's wrap modes there.
//   - a texture the surface looks up through another uv set joins the grid when that set is an affine
//     function of the grid's over the surface's vertices (render/uv_relation.h): the relation, composed
//     with the two transforms, is one more affine map A_k, and the rules above decide as for one set.
//     Any other relation leaves the two sets' texels unrelated, and the texture cannot be resampled
//     (SceneMips holds a base colour texture apart as a tint; any other refuses the grid, saying how far
//     the best affine fit misses).
// Among the textures that can be followed, the grid with the fewest texels; it may hold at most four
// times the texels of the material's largest texture (one MIP level more), else it is refused.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gltf/scene.h"
#include "mip/mip.h"
#include "render/texel_inputs.h"
#include "render/texture_set.h"

namespace svbrdf {

class UvRelations;

// The bounding box of a material's uv over its primitives' vertices, on one uv set (UvRelations).
struct UvRange {
  glm::dvec2 lo{1e300}, hi{-1e300};
  void add(glm::dvec2 uv) { lo = glm::min(lo, uv), hi = glm::max(hi, uv); }
  bool empty() const { return lo.x > hi.x; }
};

// An affine map of the plane: from one texture space to another, or one uv set to another:
// t' = linear · t + offset.
struct TextureAffine {
  glm::dmat2 linear{1.0};
  glm::dvec2 offset{0.0};
  bool identity() const { return linear == glm::dmat2(1.0) && offset == glm::dvec2(0.0); }
  bool operator==(const TextureAffine&) const = default;
};
// KHR_texture_transform's linear part R·S (textures/sampler.h apply_linear) as a matrix.
glm::dmat2 texture_transform_linear(const TextureTransform& t);
// A_k: from `grid`'s texture space to `texture`'s (both on one uv set; grid's transform invertible).
TextureAffine grid_to_texture(const TextureTransform& grid, const TextureTransform& texture);
// A_k for a texture on another uv set, `uv` the map from the grid's uv set to the texture's
// (render/uv_relation.h): T_k ∘ uv ∘ T_grid⁻¹.
TextureAffine grid_to_texture(const TextureTransform& grid, const TextureTransform& texture,
                              const TextureAffine& uv);

struct TexelGrid {
  const TexelInput* follows = nullptr;  // the slot whose uv set, transform and wrap modes the grid has
  Extent extent{0, 0};
  bool exact = true;  // every texture's texels are whole unions of grid texels
  // Per uv set, the map from the grid's uv set to it (the identity on the grid's own, on sets no
  // texture reads and past the end).
  std::vector<TextureAffine> uv;
};

// Chooses the grid for `slots` (the material's texture slots, one uv set or not; `uv` their relations
// and ranges) and fills `grid`, or says why none serves: one line naming the textures and what they lack.
std::string choose_texel_grid(const MaterialDesc& m, const std::vector<const TexelInput*>& slots,
                              const TextureSet& textures, const UvRelations& uv, TexelGrid& grid);

// `image` (read with `wrap`) resampled onto a grid of `extent` texels whose texture space `to` maps
// into the image's: each grid texel takes the image's nearest texel at its centre's image.
Image resample(const Image& image, WrapModes wrap, const TextureAffine& to, Extent extent);

}  // namespace svbrdf
