#include "render/uv_relation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace svbrdf {

namespace {

// Calls fn(primitive, vertex) once for each vertex that a triangle of a primitive drawn with material
// `index` references: the vertices the surface interpolates between (a primitive's accessors may hold
// others that no triangle reads).
template <class Fn>
void for_each_vertex(const Scene& scene, int index, Fn fn) {
  std::vector<char> seen;
  for (const Mesh& mesh : scene.meshes)
    for (const MeshPrimitive& p : mesh.primitives) {
      if (p.material != index) continue;
      seen.assign(p.positions.size(), 0);
      for (const std::uint32_t v : p.indices)
        if (v < seen.size() && !seen[v]) seen[v] = 1, fn(p, v);
    }
}

// A vertex's uv on set `set`: (0, 0) where the primitive lacks the set, as the surface reads it.
glm::dvec2 uv_at(const MeshPrimitive& p, int set, std::uint32_t v) {
  if (set < 0 || set > 1 || v >= p.texcoords[set].size()) return glm::dvec2(0.0);
  return glm::dvec2(p.texcoords[set][v]);
}

std::string texcoord(int set) { return "TEXCOORD_" + std::to_string(set); }

std::string number(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", x);
  return b;
}

// x rounded to a multiple of the power of two at or above `quantum` (see the header).
double rounded(double x, double quantum) {
  if (!(quantum > 0.0)) return x;
  const double q = std::exp2(std::ceil(std::log2(quantum)));
  return std::round(x / q) * q;
}

// A float32's unit in the last place at magnitude x.
double ulp(double x) { return x > 0.0 ? std::exp2(std::floor(std::log2(x)) - 23.0) : 0.0; }

}  // namespace

UvRelations::UvRelations(const Scene& scene, int index, const std::vector<const TexelInput*>& slots,
                         const TextureSet& textures) {
  for (const TexelInput* in : slots)
    if (std::find(sets_.begin(), sets_.end(), in->texture->uv_set()) == sets_.end())
      sets_.push_back(in->texture->uv_set());
  ranges_.resize(sets_.size());
  for_each_vertex(scene, index, [&](const MeshPrimitive& p, std::uint32_t v) {
    for (std::size_t s = 0; s < sets_.size(); ++s) ranges_[s].add(uv_at(p, sets_[s], v));
  });
  for (const int from : sets_)
    for (const int to : sets_) {
      if (from == to) continue;
      Fit& fit = fits_.emplace_back();
      fit.from = from, fit.to = to;
      // The means, and whether the two sets are the same uv at every vertex.
      glm::dvec2 mean_f(0.0), mean_t(0.0);
      double n = 0.0, largest = 0.0;
      bool identical = true;
      for_each_vertex(scene, index, [&](const MeshPrimitive& p, std::uint32_t v) {
        const glm::dvec2 f = uv_at(p, from, v), t = uv_at(p, to, v);
        mean_f += f, mean_t += t, n += 1.0;
        identical = identical && f == t;
        largest = std::max({largest, std::abs(t.x), std::abs(t.y)});
      });
      if (identical) continue;  // the identity
      mean_f /= n, mean_t /= n;
      // Least squares about the means: A = D·C⁻¹, C = Σ δf·δfᵀ, D = Σ δt·δfᵀ; b = mean_t − A·mean_f.
      glm::dmat2 c(0.0), d(0.0);
      for_each_vertex(scene, index, [&](const MeshPrimitive& p, std::uint32_t v) {
        const glm::dvec2 df = uv_at(p, from, v) - mean_f, dt = uv_at(p, to, v) - mean_t;
        c += glm::outerProduct(df, df), d += glm::outerProduct(dt, df);
      });
      // C's eigenvalues are the squared spreads of `from` along its principal axes: a ratio of spreads
      // under 2⁻²⁰ is below float32 resolution, a set whose vertices lie on a line, which leaves A
      // undetermined across it.
      const double trace = c[0][0] + c[1][1];
      if (glm::determinant(c) <= std::exp2(-40.0) * trace * trace) {
        fit.degenerate = texcoord(from) + "'s vertices lie on a line, which does not fix " + texcoord(to) +
                         " as a function of it";
        continue;
      }
      glm::dmat2 a = d * glm::inverse(c);
      // A that flattens the plane onto a line (singular values in a ratio under 2⁻²⁰, as above) would
      // map each texel of `to` onto infinitely many grid texels; said when the fit is otherwise close.
      const double frobenius = a[0][0] * a[0][0] + a[0][1] * a[0][1] + a[1][0] * a[1][0] + a[1][1] * a[1][1];
      fit.flat = std::abs(glm::determinant(a)) <= std::exp2(-20.0) * frobenius;
      // Rounded to the data's resolution (see the header).
      const UvRange& spread = range(from);
      const double extent = std::max(spread.hi.x - spread.lo.x, spread.hi.y - spread.lo.y);
      const double unit = 4.0 * ulp(largest);
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) a[i][j] = rounded(a[i][j], unit / extent);
      fit.map.linear = a;
      fit.map.offset = mean_t - a * mean_f;
      for (int i = 0; i < 2; ++i) fit.map.offset[i] = rounded(fit.map.offset[i], unit);
      // The largest miss, in each slot's texels: diag(size)·L·(uv_to − A·uv_from − b).
      std::vector<std::size_t> on;
      std::vector<glm::dmat2> to_texels;
      for (const TexelInput* in : slots) {
        if (in->texture->uv_set() != to) continue;
        on.push_back(misses_.size());
        misses_.push_back({in, from, 0.0, {}});
        const glm::dvec2 size(textures.size(*in->texture));
        to_texels.push_back(glm::dmat2(size.x, 0.0, 0.0, size.y) *
                            texture_transform_linear(in->texture->transform));
      }
      for_each_vertex(scene, index, [&](const MeshPrimitive& p, std::uint32_t v) {
        const glm::dvec2 e = uv_at(p, to, v) - (fit.map.linear * uv_at(p, from, v) + fit.map.offset);
        for (std::size_t k = 0; k < on.size(); ++k) {
          const glm::dvec2 texels = to_texels[k] * e;
          Miss& m = misses_[on[k]];
          const double miss = std::max(std::abs(texels.x), std::abs(texels.y));
          if (miss > m.texels) m.texels = miss, m.where = p.where;
        }
      });
    }
}

const UvRange& UvRelations::range(int set) const {
  static const UvRange none;
  const auto it = std::find(sets_.begin(), sets_.end(), set);
  return it == sets_.end() ? none : ranges_[std::size_t(it - sets_.begin())];
}

std::string UvRelations::relation(int from, const TexelInput& slot, TextureAffine& map) const {
  const int to = slot.texture->uv_set();
  map = TextureAffine{};
  if (to == from) return {};
  const auto fit =
      std::find_if(fits_.begin(), fits_.end(), [&](const Fit& f) { return f.from == from && f.to == to; });
  if (fit == fits_.end()) return texcoord(to) + " was not fitted against " + texcoord(from);
  if (!fit->degenerate.empty()) return fit->degenerate;
  const auto miss = std::find_if(misses_.begin(), misses_.end(),
                                 [&](const Miss& m) { return m.slot == &slot && m.from == from; });
  if (miss != misses_.end() && miss->texels > kUvRelationTolerance)
    return texcoord(to) + " is no affine function of " + texcoord(from) +
           " over the vertices: the least-squares fit misses one of " + miss->where + " by " +
           number(miss->texels) + " texels of " + slot.name + ", where " + number(kUvRelationTolerance) +
           " are allowed";
  if (fit->flat)
    return texcoord(to) + " is an affine function of " + texcoord(from) + " that flattens it onto a line";
  map = fit->map;
  return {};
}

}  // namespace svbrdf
