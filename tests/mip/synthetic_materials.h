#pragma once
// Small synthetic level-0 materials for the MIP tests, each a hard case of the BRDF pyramid in
// miniature and each defined by formulas (not by the code under test):
//   bimodal       — the spec's worked example: a flat metal, 80 % α = 0.05 and 20 % α = 0.4 texels;
//   tray          — metal-tray-like: polished steel (α ≈ 0.05–0.1) with rough fingerprint whorls;
//   painted_wall  — a white dielectric paint, roughness 0.7, on bumps from a height field;
//   paper         — albedo only: ink strokes on paper, flat, one roughness (the control);
//   sandstone     — colored grains (red/ochre/buff) on gentle bumps, rough;
//   granite       — glossy mica flecks with tilted normals in a rough matrix (the glint regime).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include <glm/glm.hpp>

#include "appearance/rng.h"
#include "textures/material_texels.h"

namespace svbrdf::synthetic {

inline constexpr double kPi = 3.14159265358979323846;

// Roughness from α.
inline float roughness_of_alpha(double alpha) { return static_cast<float>(std::sqrt(alpha)); }

// Exactly 20 % of the texels rough (α = 0.4), the rest α = 0.05, shuffled with a fixed seed, so every
// level's whole-texture mean is the worked example's mixture.
inline MaterialTexels bimodal(int size, glm::vec3 base_color = glm::vec3(0.95f, 0.93f, 0.88f)) {
  MaterialTexels m(size, size);
  std::vector<int> order(m.size());
  std::iota(order.begin(), order.end(), 0);
  Rng rng(7, 3);
  for (std::size_t k = order.size() - 1; k > 0; --k)
    std::swap(order[k], order[static_cast<std::size_t>(rng.next_double() * double(k + 1))]);
  const std::size_t rough = m.size() / 5;
  for (std::size_t k = 0; k < m.size(); ++k) {
    const auto t = static_cast<std::size_t>(order[k]);
    m.base_color[t] = base_color;
    m.metallic[t] = 1.0f;
    m.roughness[t] = roughness_of_alpha(k < rough ? 0.4 : 0.05);
  }
  return m;
}

// A smooth periodic field in [−1, 1]: a few sines of integer frequencies (tiles seamlessly).
inline double waves(double x, double y, int seed) {
  Rng rng(static_cast<std::uint64_t>(seed), 17);
  double v = 0, total = 0;
  for (int k = 0; k < 6; ++k) {
    const int fx = 1 + static_cast<int>(rng.next_float() * 5), fy = 1 + static_cast<int>(rng.next_float() * 5);
    const double phase = rng.next_double() * 2 * kPi, amp = 1.0 / (1 + k);
    v += amp * std::sin(2 * kPi * (fx * x + fy * y) + phase);
    total += amp;
  }
  return v / total;
}

// Unit normals of a height field h(x, y) (periodic, in texel units of the level-0 image) with slope
// scale `strength`: n = normalize(−∂h/∂x, +∂h/∂y, 1) (rows go down the image, +Y up as glTF says).
template <class Height>
void set_normals_from_height(MaterialTexels& m, Height h, double strength) {
  for (int j = 0; j < m.height; ++j)
    for (int i = 0; i < m.width; ++i) {
      const double dx = (h((i + 1) % m.width, j) - h((i + m.width - 1) % m.width, j)) * 0.5;
      const double dy = (h(i, (j + 1) % m.height) - h(i, (j + m.height - 1) % m.height)) * 0.5;
      m.normal[m.index(i, j)] = glm::normalize(glm::vec3(float(-strength * dx), float(strength * dy), 1.0f));
    }
}

// Bumps of about `cell` texels: value noise on a periodic lattice, smoothly interpolated.
inline std::vector<double> bump_field(int size, int cell, int seed) {
  const int cells = std::max(1, size / cell);
  std::vector<double> lattice(static_cast<std::size_t>(cells) * cells);
  Rng rng(static_cast<std::uint64_t>(seed), 23);
  for (double& v : lattice) v = rng.next_double();
  std::vector<double> h(static_cast<std::size_t>(size) * size);
  auto s = [](double t) { return t * t * (3 - 2 * t); };
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double fx = (i + 0.5) / cell, fy = (j + 0.5) / cell;
      const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
      const double tx = s(fx - x0), ty = s(fy - y0);
      auto L = [&](int x, int y) {
        return lattice[static_cast<std::size_t>(((y % cells) + cells) % cells) * cells + ((x % cells) + cells) % cells];
      };
      const double a = L(x0, y0) * (1 - tx) + L(x0 + 1, y0) * tx, b = L(x0, y0 + 1) * (1 - tx) + L(x0 + 1, y0 + 1) * tx;
      h[static_cast<std::size_t>(j) * size + i] = (a * (1 - ty) + b * ty) * cell;
    }
  return h;
}

inline MaterialTexels painted_wall(int size) {
  MaterialTexels m(size, size);
  const auto h = bump_field(size, 4, 5);
  const auto h2 = bump_field(size, 16, 9);
  for (std::size_t k = 0; k < m.size(); ++k) {
    m.base_color[k] = glm::vec3(0.80f, 0.78f, 0.72f);
    m.metallic[k] = 0.0f;
    m.roughness[k] = 0.7f;
  }
  set_normals_from_height(m, [&](int i, int j) {
    const std::size_t t = static_cast<std::size_t>(j) * size + i;
    return 0.5 * h[t] + 0.25 * h2[t];
  }, 0.6);
  return m;
}

inline MaterialTexels tray(int size) {
  MaterialTexels m(size, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double x = (i + 0.5) / size, y = (j + 0.5) / size;
      // Polished steel whose α drifts between 0.05 and 0.1; fingerprint whorls (ridges of a
      // periodic field, masked by blobs) are rough.
      const double drift = 0.5 + 0.5 * waves(x, y, 3);
      const double blob = waves(x, y, 11);
      const double ridges = std::sin(2 * kPi * (18 * x + 4 * waves(x, y, 13)));
      const bool print = blob > 0.25 && ridges > 0.2;
      const std::size_t k = m.index(i, j);
      m.base_color[k] = glm::vec3(0.91f, 0.92f, 0.92f);
      m.metallic[k] = 1.0f;
      m.roughness[k] = print ? 0.6f : roughness_of_alpha(0.05 + 0.05 * drift);
    }
  return m;
}

inline MaterialTexels paper(int size) {
  MaterialTexels m(size, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double x = (i + 0.5) / size, y = (j + 0.5) / size;
      const bool ink = std::sin(2 * kPi * 12 * y) > 0.6 && waves(x, y, 21) > -0.3;
      const std::size_t k = m.index(i, j);
      m.base_color[k] = ink ? glm::vec3(0.03f, 0.04f, 0.12f) : glm::vec3(0.85f, 0.84f, 0.80f);
      m.metallic[k] = 0.0f;
      m.roughness[k] = 0.6f;
    }
  return m;
}

inline MaterialTexels sandstone(int size) {
  MaterialTexels m(size, size);
  Rng rng(31, 2);
  const glm::vec3 colors[3] = {{0.45f, 0.16f, 0.08f}, {0.60f, 0.40f, 0.14f}, {0.72f, 0.62f, 0.45f}};
  for (std::size_t k = 0; k < m.size(); ++k) {
    m.base_color[k] = colors[static_cast<int>(rng.next_float() * 3) % 3];
    m.metallic[k] = 0.0f;
    m.roughness[k] = 0.85f + 0.1f * rng.next_float();
  }
  const auto h = bump_field(size, 8, 41);
  set_normals_from_height(m, [&](int i, int j) { return h[static_cast<std::size_t>(j) * size + i]; }, 0.3);
  return m;
}

inline MaterialTexels granite(int size) {
  MaterialTexels m(size, size);
  Rng rng(37, 4);
  for (std::size_t k = 0; k < m.size(); ++k) {
    const bool mica = rng.next_float() < 0.15f;
    const float g = 0.2f + 0.5f * rng.next_float();
    m.base_color[k] = mica ? glm::vec3(0.05f) : glm::vec3(g, g * 0.95f, g * 0.9f);
    m.metallic[k] = 0.0f;
    m.roughness[k] = mica ? 0.1f : 0.8f;
    if (mica) {
      const double tilt = 20.0 * kPi / 180 * rng.next_double(), phi = 2 * kPi * rng.next_double();
      m.normal[k] = glm::vec3(float(std::sin(tilt) * std::cos(phi)), float(std::sin(tilt) * std::sin(phi)), float(std::cos(tilt)));
    }
  }
  return m;
}

// Orange peel: the fingerprinted metal tray under a coat with its own bumps (a coat normal map), a
// patchy clearcoat weight (1 or 0.3) and roughness (0.05 or 0.3), all independent of the base's maps.
inline MaterialTexels orange_peel(int size) {
  MaterialTexels m = tray(size);
  MaterialTexels bumps(size, size);
  const auto h = bump_field(size, 8, 17);
  set_normals_from_height(bumps, [&](int i, int j) { return h[static_cast<std::size_t>(j) * size + i]; }, 0.3);
  m.clearcoat_normal = bumps.normal;
  m.clearcoat_factor = 1.0f;
  m.clearcoat_roughness_factor = 1.0f;
  m.clearcoat.resize(m.size());
  m.clearcoat_roughness.resize(m.size());
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const std::size_t k = m.index(i, j);
      m.clearcoat[k] = waves(double(i) / size, double(j) / size, 3) > 0 ? 1.0f : 0.3f;
      m.clearcoat_roughness[k] = waves(double(i) / size, double(j) / size, 4) > 0 ? 0.05f : 0.3f;
    }
  return m;
}

}  // namespace svbrdf::synthetic
