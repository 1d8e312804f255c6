#include <benchmark/benchmark.h>

#include "appearance/frame.h"
#include "appearance/rng.h"

namespace {

void BM_FrameFromNormal(benchmark::State& state) {
  svbrdf::Rng rng(1, 1);
  glm::vec3 n = glm::normalize(glm::vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, 1));
  for (auto _ : state) {
    const svbrdf::Frame f = svbrdf::Frame::from_normal(n);
    benchmark::DoNotOptimize(f);
    n = glm::normalize(n + glm::vec3(1e-3f, 0, 0));
  }
}
BENCHMARK(BM_FrameFromNormal);

}  // namespace
