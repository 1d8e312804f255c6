#include "mip/coat_layer.h"

#include <array>
#include <vector>

#include "mip/direction_grid.h"
#include "mip/lobe_reduction.h"

namespace svbrdf {

template <class T>
void accumulate_coat(std::span<const Lobe> base_lobes, const CoatTexel& coat, std::span<const glm::dvec3> base,
                     std::span<const glm::dvec3> base_coated, double scale, std::span<glm::dvec3> table) {
  const DirectionGrid& g = DirectionGrid::get();
  // What depends on wo alone (the coat's Fresnel) once per direction, the shapes once per texel.
  std::array<T, DirectionGrid::kDirections> fresnel{};
  for (int d = 0; d < DirectionGrid::kDirections; ++d)
    fresnel[static_cast<std::size_t>(d)] = coat_fresnel(coat, glm::vec<3, T>(g.direction(d)));
  std::array<LobeShape<T>, kMaxLobes> shapes, base_shapes;
  const std::size_t n = std::min<std::size_t>(coat.lobes.size(), kMaxLobes);
  const std::size_t nb = std::min<std::size_t>(base_lobes.size(), kMaxLobes);
  for (std::size_t k = 0; k < n; ++k) shapes[k] = lobe_shape<T>(coat.lobes[k]);
  for (std::size_t k = 0; k < nb; ++k) base_shapes[k] = lobe_shape<T>(base_lobes[k], false);
  for (int p = 0; p < DirectionGrid::kPairs; ++p) {
    const std::size_t q = static_cast<std::size_t>(p);
    const PairTerms<T>* pt;
    if constexpr (std::is_same_v<T, double>) pt = &g.pair_d(p);
    else pt = &g.pair_f(p);
    glm::vec<3, T> c(0);
    const T cosine = coat_cosine(base_lobes.first(nb), base_shapes.data(), *pt);
    if (cosine > 0)
      for (std::size_t k = 0; k < n; ++k) c += coat_lobe_eval(coat.lobes[k], shapes[k], *pt);
    const double f = fresnel[static_cast<std::size_t>(DirectionGrid::wo_index(p))];
    table[q] += scale * (base[q] - f * base_coated[q] + glm::dvec3(cosine * c));
  }
}

template void accumulate_coat<float>(std::span<const Lobe>, const CoatTexel&, std::span<const glm::dvec3>,
                                     std::span<const glm::dvec3>, double, std::span<glm::dvec3>);
template void accumulate_coat<double>(std::span<const Lobe>, const CoatTexel&, std::span<const glm::dvec3>,
                                      std::span<const glm::dvec3>, double, std::span<glm::dvec3>);

void accumulate_coated_double(std::span<const Lobe> base, const CoatTexel& coat, double scale, std::span<glm::dvec3> table) {
  if (!coat.present()) {
    for (const Lobe& l : base) accumulate_lobe_double(l, scale, table);
    return;
  }
  static thread_local BrdfTable b, bc;
  b.assign(DirectionGrid::kPairs, glm::dvec3(0));
  bc.assign(DirectionGrid::kPairs, glm::dvec3(0));
  for (const Lobe& l : base) {
    accumulate_lobe_double(l, 1.0, b);
    if (l.coat > 0) accumulate_lobe_double(l, l.coat, bc);
  }
  accumulate_coat<double>(base, coat, b, bc, scale, table);
}

}  // namespace svbrdf
