#pragma once
// How a material's uv sets follow one another, so that textures on two of them can share one texel
// grid (render/texel_grid.h, docs/design-notes.md "Textures on two uv sets ...").
//
// A BRDF-averaged texel is the mean f_eff over the surface points it covers, which needs every
// parameter at the same points. Two uv sets are independent vertex data: a texel of a texture on
// TEXCOORD_1 covers the surface points whose TEXCOORD_1 falls in it, in general not those of any
// texel on TEXCOORD_0. One grid can hold both only where one set is a function of the other that the
// grid's maps express — an affine one, uv_s = A·uv_f + b (A 2×2): composed with the textures'
// KHR_texture_transforms it is the affine map from the grid's texture space to each texture's that
// the grid already takes (grid_to_texture), and its rules on texel shares, size and wrap modes then
// decide as for one uv set. Blender exports carry such pairs: two identical maps (A = I, b = 0), or
// one the other scaled and offset. Any other relation — a lightmap pack, a swirl, one set per island —
// maps one set's texels onto the other's unevenly and is refused.
//
// The fit: A and b by least squares over the vertices that the triangles of the material's
// primitives reference (a vertex without the set reads uv (0, 0), as the surface does), accepted
// when it misses no vertex by more than kUvRelationTolerance texels of any texture on the set it
// gives, measured in that texture's texels (its size and KHR_texture_transform): those are the
// textures the relation places on the grid (the grid's own set's are read as they lie), so the grid
// on either set may serve, each placing the other's textures. Inside a triangle
// both sets are interpolated linearly, so the miss is affine in the barycentrics and no point misses
// by more than the triangle's vertices do: the vertices bound the whole surface.
//
// The fitted b is rounded to a power of two near 4 units in the last place of the largest float32 uv
// the set gives, and A to that over the extent of the set it reads: the data's own rounding (half a
// unit at each vertex) moves a least-squares fit by about that much, so the data tell no two values
// closer apart. A relation that is exactly a scale and an offset then composes into a map exactly
// axis-aligned, as the grid's rules on clamped axes ask, and the miss is measured for the rounded map.
// Identical sets (every vertex's two uv equal) are the identity, whatever their spread.
#include <string>
#include <vector>

#include "gltf/scene.h"
#include "render/texel_grid.h"
#include "render/texel_inputs.h"
#include "render/texture_set.h"

namespace svbrdf {

// The largest miss a relation may have at a vertex, in texels of the finest texture on the set it
// gives. A miss of e texels moves where the grid holds a texel's edges, relative to where the surface
// reads them, by at most e along each axis, so at most 2e of any texel's area (1 − (1 − e)²) takes a
// neighbour's parameters, and any average over whole texels — every MIP level — moves by at most 2e
// times a parameter's range. 2e ≤ 1/510, half a step of an 8-bit texture (glTF's PNG and JPEG), keeps
// that below what the textures resolve: e = 1/1020.
constexpr double kUvRelationTolerance = 1.0 / 1020.0;

// The relations between the uv sets a material's texture slots read, and their ranges.
class UvRelations {
 public:
  // For material `index` of `scene` and its texture slots `slots` (render/texel_inputs.h; they must
  // outlive this): the uv range of each set they read, and between each two of those sets the fit both
  // ways, with its miss in the texels of each slot on the set it gives.
  UvRelations(const Scene& scene, int index, const std::vector<const TexelInput*>& slots,
              const TextureSet& textures);

  // The uv range of set `set` (texel_grid.h's wrap rule; empty when no slot reads it).
  const UvRange& range(int set) const;
  // The map from uv set `from` to the uv `slot` reads (the identity on its own set) into `map`; or
  // why there is none: its set is no affine function of `from` within the tolerance, the miss found
  // named in `slot`'s texels.
  std::string relation(int from, const TexelInput& slot, TextureAffine& map) const;

 private:
  struct Fit {
    int from = 0, to = 0;
    TextureAffine map;
    std::string degenerate;  // why no map serves, whatever the textures (empty: the fit is one)
    bool flat = false;       // A maps the plane onto a line
  };
  struct Miss {
    const TexelInput* slot = nullptr;
    int from = 0;
    double texels = 0.0;  // the largest miss at a vertex, in the slot's texels
    std::string where;    // the primitive of that vertex
  };
  std::vector<int> sets_;  // the sets the slots read
  std::vector<UvRange> ranges_;
  std::vector<Fit> fits_;
  std::vector<Miss> misses_;
};

}  // namespace svbrdf
