#include "render/texel_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>

#include "render/uv_relation.h"

namespace svbrdf {

namespace {

bool near_integer(double x, double tolerance) { return std::abs(x - std::round(x)) <= tolerance; }

const char* wrap_name(WrapMode w) {
  switch (w) {
    case WrapMode::repeat:
      return "repeat";
    case WrapMode::clamp_to_edge:
      return "clamp-to-edge";
    case WrapMode::mirrored_repeat:
      return "mirrored repeat";
  }
  return "?";
}

WrapMode axis_wrap(const Sampler& s, int axis) { return axis == 0 ? s.wrap_s : s.wrap_t; }

std::string number(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", x);
  return b;
}

// How the texels of each texture lie on an axis of `n` grid texels (see the header), the worst of them:
// exact — every texture texel is a whole number q of grid texels, its edges on grid texel edges (A_k's
// column of that axis has one nonzero component b, a texture texel spans q grid texels, and the offset
// is a multiple of 1/q texel); displaced — whole numbers of grid texels, but shifted off their edges by
// less than one: the grid holds each texture displaced by at most half a grid texel, the same
// everywhere; aliased — texels of fractional width (or turned): grid texels fall unevenly on them.
enum class Fit { exact, displaced, aliased };
Fit fit(const std::vector<TextureAffine>& maps, const std::vector<glm::ivec2>& sizes, int axis, int n,
        std::size_t* worst = nullptr) {
  Fit f = Fit::exact;
  for (std::size_t k = 0; k < maps.size(); ++k) {
    const glm::dvec2 col = maps[k].linear[axis];
    const int b = std::abs(col.x) >= std::abs(col.y) ? 0 : 1;
    const double q =
        col[b] == 0.0 ? 0.0 : double(n) / (std::abs(col[b]) * sizes[k][b]);  // grid texels a texel
    Fit here = Fit::exact;
    // The other component's share of a grid texel, in texels: a transform's float rotation by a quarter
    // turn leaves ~1e-8 there.
    const double across = std::abs(col[1 - b]) * sizes[k][1 - b] / n;
    if (across > 1e-4 || q == 0.0 || !near_integer(q, 1e-4 * q))
      here = Fit::aliased;
    else if (!near_integer(maps[k].offset[b] * sizes[k][b] * std::round(q), 1e-3))
      here = Fit::displaced;
    if (here > f) {
      f = here;
      if (worst) *worst = k;
    }
  }
  return f;
}

// The uv sets `slots` read, each with its textures, in the slots' order: "TEXCOORD_0: a, b; TEXCOORD_1: c".
std::string uv_sets(const std::vector<const TexelInput*>& slots) {
  std::string sets;
  int last = 0;
  for (const TexelInput* in : slots) last = std::max(last, in->texture->uv_set());
  for (int n = 0; n <= last; ++n) {
    std::string names;
    for (const TexelInput* in : slots)
      if (in->texture->uv_set() == n) names += (names.empty() ? "" : ", ") + in->name;
    if (!names.empty()) sets += (sets.empty() ? "" : "; ") + ("TEXCOORD_" + std::to_string(n)) + ": " + names;
  }
  return sets;
}

// The grid that follows slot `g` (see the header), or why it cannot.
std::string grid_following(const TexelInput& g, const std::vector<const TexelInput*>& slots,
                           const TextureSet& textures, const UvRelations& relations, std::size_t largest,
                           TexelGrid& grid) {
  const TextureTransform& tg = g.texture->transform;
  if (glm::determinant(texture_transform_linear(tg)) == 0.0)
    return g.name + "'s KHR_texture_transform has a zero scale (its texture space does not map back to uv)";
  const Sampler& gs = textures.sampler(*g.texture);
  const int set = g.texture->uv_set();
  const UvRange& range = relations.range(set);
  // A texture on another uv set reaches the grid through the relation of the sets (uv_relation.h).
  std::vector<TextureAffine> uv;
  std::vector<TextureAffine> maps;
  std::vector<glm::ivec2> sizes;
  for (const TexelInput* in : slots) {
    TextureAffine relation;
    if (const std::string why = relations.relation(set, *in, relation); !why.empty())
      return "its textures read different uv sets (" + uv_sets(slots) + "), and " + why +
             "; they share no texel grid, and only a baseColorTexture is held apart on its own set";
    const int k = in->texture->uv_set();
    if (k >= 0 && !relation.identity()) {
      if (uv.size() <= std::size_t(k)) uv.resize(std::size_t(k) + 1);
      uv[std::size_t(k)] = relation;
    }
    maps.push_back(grid_to_texture(tg, in->texture->transform, relation));
    sizes.push_back(textures.size(*in->texture));
  }
  // The surface's uv range in the grid's texture space: the images of its box's corners.
  glm::dvec2 lo(0.0), hi(1.0);
  if (!range.empty()) {
    const TextureAffine to_grid{texture_transform_linear(tg), glm::dvec2(tg.offset)};
    lo = glm::dvec2(1e300), hi = glm::dvec2(-1e300);
    for (const glm::dvec2 c :
         {range.lo, range.hi, glm::dvec2(range.lo.x, range.hi.y), glm::dvec2(range.hi.x, range.lo.y)}) {
      const glm::dvec2 t = to_grid.linear * c + to_grid.offset;
      lo = glm::min(lo, t), hi = glm::max(hi, t);
    }
  }
  for (int a = 0; a < 2; ++a) {
    constexpr double kEdge = 1e-6;  // a vertex on the square's edge reads inside it
    if (lo[a] >= -kEdge && hi[a] <= 1.0 + kEdge) continue;
    const WrapMode gw = axis_wrap(gs, a);
    const std::string where = " along " + std::string(a ? "t" : "s") + ", where the surface's TEXCOORD_" +
                              std::to_string(g.texture->uv_set()) + " reaches [" + number(lo[a]) + ", " +
                              number(hi[a]) + "] of " + g.name + "'s texture space";
    for (std::size_t k = 0; k < slots.size(); ++k) {
      const TextureAffine& m = maps[k];
      const Sampler& ks = textures.sampler(*slots[k]->texture);
      const std::string who =
          slots[k]->name + " does not continue as " + g.name + "'s " + wrap_name(gw) + where;
      if (gw == WrapMode::repeat) {
        const glm::dvec2 col = m.linear[a];
        for (int b = 0; b < 2; ++b) {
          if (!near_integer(col[b], 1e-6 * std::max(1.0, std::abs(col[b]))))
            return who + " (its KHR_texture_transform moves it by " + number(col[b]) +
                   " of its periods along " + (b ? "t" : "s") +
                   " per period of the grid, not a whole number)";
          // Repeat has period 1, mirrored repeat period 2 (an even move), clamp-to-edge none.
          const double moves = std::round(col[b]);
          const WrapMode kw = axis_wrap(ks, b);
          const bool periodic =
              kw == WrapMode::repeat || (kw == WrapMode::mirrored_repeat && near_integer(moves / 2.0, 0.0));
          if (moves != 0.0 && !periodic)
            return who + " (it moves by " + number(moves) + " of its periods along " + (b ? "t" : "s") +
                   " per period of the grid, and its wrap mode there is " + wrap_name(kw) + ")";
        }
      } else {
        const bool same_axis = std::abs(m.linear[a][a] - 1.0) < 1e-9 && m.linear[a][1 - a] == 0.0 &&
                               m.linear[1 - a][a] == 0.0 && std::abs(m.offset[a]) < 1e-9;
        if (!same_axis) return who + " (its KHR_texture_transform differs along that axis)";
        if (axis_wrap(ks, a) != gw)
          return who + " (its wrap mode there is " + wrap_name(axis_wrap(ks, a)) + ")";
      }
    }
  }
  // The size: every texture's texels across the grid's unit, then the smallest multiple that fits.
  int base[2] = {1, 1};
  const TexelInput* finest[2] = {&g, &g};
  for (std::size_t k = 0; k < slots.size(); ++k)
    for (int a = 0; a < 2; ++a) {
      const glm::dvec2 col = maps[k].linear[a];
      const double across = std::max(std::abs(col.x) * sizes[k].x, std::abs(col.y) * sizes[k].y);
      const int texels = int(std::min(std::ceil(across - 1e-6), 1e9));
      if (texels > base[a]) base[a] = texels, finest[a] = slots[k];
    }
  const double cap = 4.0 * double(largest);
  if (double(base[0]) * double(base[1]) > cap)
    return "on " + g.name + "'s grid, " + finest[0]->name +
           (finest[1] == finest[0] ? "" : " and " + finest[1]->name) +
           (finest[1] == finest[0] ? " needs " : " need ") + std::to_string(base[0]) + "x" +
           std::to_string(base[1]) + " texels across its [0, 1]², more than four times the largest texture's";
  // Per axis the smallest multiple that fits exactly, and the smallest that fits displaced.
  int exact_n[2] = {0, 0}, displaced_n[2] = {0, 0};
  for (int a = 0; a < 2; ++a)
    for (int m = 1; m <= 4 && double(base[a]) * m <= cap; ++m) {
      const Fit f = fit(maps, sizes, a, base[a] * m);
      if (f == Fit::exact && !exact_n[a]) exact_n[a] = m;
      if (f != Fit::aliased && !displaced_n[a]) displaced_n[a] = m;
    }
  for (int a = 0; a < 2; ++a)
    if (!displaced_n[a]) {
      std::size_t k = 0;
      fit(maps, sizes, a, base[a], &k);
      const glm::dvec2 col = maps[k].linear[a];
      return "on " + g.name + "'s grid, " + slots[k]->name + "'s texels span " +
             number(base[a] / std::max(std::abs(col.x) * sizes[k].x, std::abs(col.y) * sizes[k].y)) +
             " grid texels along " + (a ? "t" : "s") +
             (std::min(std::abs(col.x), std::abs(col.y)) > 1e-6 ? ", turned by its KHR_texture_transform"
                                                                : "") +
             ", and no multiple up to 4 holds them whole: nearest resampling would weigh its texels unevenly";
    }
  // Exact on both axes if the size allows, else displaced on the fewest.
  const int options[4][2] = {{exact_n[0], exact_n[1]},
                             {exact_n[0], displaced_n[1]},
                             {displaced_n[0], exact_n[1]},
                             {displaced_n[0], displaced_n[1]}};
  const int* n = nullptr;
  for (const auto& o : options)
    if (o[0] && o[1] && double(base[0] * o[0]) * double(base[1] * o[1]) <= cap) {
      n = o;
      break;
    }
  if (!n) {
    std::size_t k = 0;
    if (fit(maps, sizes, 0, base[0], &k) == Fit::exact) fit(maps, sizes, 1, base[1], &k);
    return "on " + g.name + "'s grid, " + slots[k]->name + "'s texels lie whole only on a grid of " +
           std::to_string(base[0] * displaced_n[0]) + "x" + std::to_string(base[1] * displaced_n[1]) +
           " texels, more than four times the largest texture's";
  }
  const bool exact = n[0] == exact_n[0] && n[1] == exact_n[1];
  grid.follows = &g;
  grid.extent = {base[0] * n[0], base[1] * n[1]};
  grid.exact = exact;
  grid.uv = std::move(uv);
  return {};
}

}  // namespace

glm::dmat2 texture_transform_linear(const TextureTransform& t) {
  const double c = std::cos(double(t.rotation())), s = std::sin(double(t.rotation()));
  // Columns: the images of the uv axes.
  return glm::dmat2(glm::dvec2(c, -s) * double(t.scale.x), glm::dvec2(s, c) * double(t.scale.y));
}

TextureAffine grid_to_texture(const TextureTransform& grid, const TextureTransform& texture,
                              const TextureAffine& uv) {
  if (uv.identity()) return grid_to_texture(grid, texture);
  // t_k = L_k·(R·uv_g + r) + o_k with uv_g = L_g⁻¹·(t_g − o_g).
  const glm::dmat2 lk = texture_transform_linear(texture);
  TextureAffine a;
  a.linear = lk * uv.linear * glm::inverse(texture_transform_linear(grid));
  a.offset = lk * uv.offset + glm::dvec2(texture.offset) - a.linear * glm::dvec2(grid.offset);
  return a;
}

TextureAffine grid_to_texture(const TextureTransform& grid, const TextureTransform& texture) {
  // t_k = L_k·uv + o_k with uv = L_g⁻¹·(t_g − o_g).
  TextureAffine a;
  a.linear = texture_transform_linear(texture) * glm::inverse(texture_transform_linear(grid));
  a.offset = glm::dvec2(texture.offset) - a.linear * glm::dvec2(grid.offset);
  // Equal transforms map exactly onto each other (the inverse's rounding aside).
  if (same_transform(grid, texture)) a = TextureAffine{};
  return a;
}

std::string choose_texel_grid(const MaterialDesc& m, const std::vector<const TexelInput*>& slots,
                              const TextureSet& textures, const UvRelations& relations, TexelGrid& grid) {
  std::size_t largest = 0;
  for (const TexelInput* in : slots) {
    const TextureRef& r = *in->texture;
    if ((&r == &m.normal_texture || &r == &m.clearcoat_normal_texture) &&
        textures.channels(r) < 3)
      return in->name + " has fewer than three channels";
    const glm::ivec2 size = textures.size(r);
    largest = std::max(largest, std::size_t(size.x) * std::size_t(size.y));
  }
  // Every texture as a candidate to follow; the grid of fewest texels (the first among equals).
  std::string first_why;
  bool found = false;
  for (const TexelInput* g : slots) {
    TexelGrid candidate;
    const std::string why = grid_following(*g, slots, textures, relations, largest, candidate);
    if (!why.empty()) {
      if (first_why.empty()) first_why = why;
      continue;
    }
    const auto texels = [](Extent e) { return std::size_t(e.width) * std::size_t(e.height); };
    if (!found || texels(candidate.extent) < texels(grid.extent)) grid = candidate;
    found = true;
  }
  return found ? std::string() : first_why;
}

Image resample(const Image& image, WrapModes wrap, const TextureAffine& to, Extent extent) {
  Image out(extent.width, extent.height, image.channels);
  const std::size_t c = static_cast<std::size_t>(image.channels);
  tbb::parallel_for(0, extent.height, [&](int j) {
    for (int i = 0; i < extent.width; ++i) {
      const glm::dvec2 centre((i + 0.5) / extent.width, (j + 0.5) / extent.height);
      const glm::dvec2 t = to.linear * centre + to.offset;
      // The texel the level0 lookup reads at t (textures/sampler.h).
      const int x = nearest_texel_index(static_cast<float>(t.x), image.width, wrap.s);
      const int y = nearest_texel_index(static_cast<float>(t.y), image.height, wrap.t);
      const float* src = &image.pixels[(static_cast<std::size_t>(y) * image.width + x) * c];
      std::copy(src, src + c, &out.pixels[(static_cast<std::size_t>(j) * extent.width + i) * c]);
    }
  });
  return out;
}

}  // namespace svbrdf
