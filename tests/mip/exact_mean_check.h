#pragma once
// The checks every layer's tests share: a coarse texel's exact reference (mip/exact_reference.h) is the
// mean of its level-0 texels' f_eff, each given by an independent transcription of the layer's
// specification in double; and the reference's table is its evaluation.
#include <gtest/gtest.h>

#include <array>

#include "appearance/rng.h"
#include "mip/exact_reference.h"
#include "random_directions.h"

namespace svbrdf::testing_directions {

// 200 trials over levels 1–3 of `m` (a square material of at least 8×8 texels): a random texel and a
// random pair of directions (wi below the surface where `wi_below`: the transmissions'), the reference
// against the mean of f_eff(x, y, wi, wo) over the level-0 texels (x, y) it covers, to 1e-6 relative.
template <class FEff>
void expect_coarse_exact_is_the_mean(const MaterialTexels& m, Rng& rng, const FEff& f_eff, bool wi_below = false) {
  const ExactReference exact(m);
  for (int trial = 0; trial < 200; ++trial) {
    const int level = 1 + trial % 3, n = m.width >> level;
    const int i = int(rng.next_u32() % unsigned(n)), j = int(rng.next_u32() % unsigned(n));
    glm::dvec3 wi = random_above(rng);
    const glm::dvec3 wo = random_above(rng);
    if (wi_below) wi.z = -wi.z;
    glm::dvec3 sum(0);
    for (int y = j << level; y < (j + 1) << level; ++y)
      for (int x = i << level; x < (i + 1) << level; ++x) sum += f_eff(x, y, wi, wo);
    const glm::dvec3 want = sum / double(1 << (2 * level)), got = exact.eval(level, i, j, wi, wo);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-6 * want[c] + 1e-12) << "level " << level;
  }
}

// The reference's table over the metric's pairs (direction_grid.h, its own loop) is its evaluation at
// those pairs, at a texel of levels 0, 1 and 2 of `m` (at least 4×4 texels).
inline void expect_exact_table_is_its_evaluation(const MaterialTexels& m) {
  const ExactReference exact(m);
  const DirectionGrid& g = DirectionGrid::get();
  for (const auto& [level, i, j] : {std::array{0, 1, 2}, std::array{1, 1, 0}, std::array{2, 0, 0}}) {
    const BrdfTable t = exact.table(level, i, j);
    for (int p = 0; p < DirectionGrid::kPairs; p += 7) {
      const glm::dvec3 want = exact.eval(level, i, j, g.direction(DirectionGrid::wi_index(p)), g.direction(DirectionGrid::wo_index(p)));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[static_cast<std::size_t>(p)][c], want[c], 1e-12 + 1e-9 * want[c]) << "pair " << p;
    }
  }
}

}  // namespace svbrdf::testing_directions
