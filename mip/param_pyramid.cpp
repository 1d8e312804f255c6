#include "mip/param_pyramid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "base/error.h"
#include "base/huge_pages.h"
#include "mip/coat_layer.h"
#include "mip/diffuse_transmission.h"
#include "mip/exact_reference.h"
#include "mip/sheen_layer.h"

namespace svbrdf {

namespace {

// The unit direction of a mean of unit normals, and the α² a filter adds for its length r: r == 1
// (flat) widens nothing; r → 0 (normals cancel) widens to the roughest lobe.
struct MeanNormal {
  glm::vec3 n{0, 0, 1};
  float widen = 0.0f;
};
MeanNormal mean_normal(const glm::vec3& mean, TextureFilter filter) {
  MeanNormal out;
  const float len = glm::length(mean), r = std::min(1.0f, len);
  if (r > 0) out.n = mean / len;
  if (filter == TextureFilter::toksvig) {
    out.widen = r > 0 ? 2.0f * (1.0f - r) / r : 1.0f;
  } else if (filter == TextureFilter::vmf) {
    const float kappa = r < 1.0f ? (3.0f * r - r * r * r) / (1.0f - r * r) : INFINITY;
    out.widen = kappa > 0 ? 2.0f / kappa : 1.0f;
  }
  return out;
}

}  // namespace

Lobe param_lobe(const ParamTexel& t, TextureFilter filter, const SpecularLayer& layer, const AnisotropyLayer& aniso,
                float transmission, const DiffuseTransmissionLayer& diffuse_transmission) {
  const MeanNormal m = mean_normal(t.normal, filter);
  Lobe l = lobe_from_texel(t.base_color, t.metallic, t.roughness, m.n, 1.0f, layer, aniso, transmission);
  add_diffuse_transmission(l, t.metallic, layer, transmission, diffuse_transmission);
  l.alpha2 = std::min(1.0f, l.alpha2 + m.widen);
  // The transmission goes through the widened shape too: a texel's transmits through its own α² (lobe.h).
  if (l.transmission_alpha2 > 0.0f) l.transmission_alpha2 = l.alpha2;
  return l;
}

Lobe param_coat_lobe(const ParamCoat& c, TextureFilter filter) {
  const MeanNormal m = mean_normal(c.normal, filter);
  Lobe l = coat_lobe(CoatLayer{c.clearcoat, c.roughness, m.n});
  l.alpha2 = std::min(1.0f, l.alpha2 + m.widen);
  return l;
}

ParamLobes param_lobes(const ParamTexel& t, TextureFilter filter, const SpecularLayer& layer, const ParamCoat* coat,
                       const SheenLayer* sheen, const AnisotropyLayer* aniso, float transmission,
                       const DiffuseTransmissionLayer* diffuse_transmission) {
  ParamLobes out;
  out.base = param_lobe(t, filter, layer, aniso ? *aniso : AnisotropyLayer{}, transmission,
                        diffuse_transmission ? *diffuse_transmission : DiffuseTransmissionLayer{});
  if (sheen) {
    out.sheen = *sheen;
    out.base.sheen = sheen_share(*sheen);
  }
  if (coat) {
    out.base.coat = std::clamp(coat->clearcoat, 0.0f, 1.0f);
    out.coat = param_coat_lobe(*coat, filter);
    out.coated = true;
  }
  return out;
}

namespace {

// Each texel of `level` from its children in `fine`: mean(children) gets a function that calls its
// argument with each child and the child's weight, the level-0 texels it covers.
template <class T, class Mean>
std::vector<T> level_from_below(Extent level0, int level, const std::vector<T>& fine, const Mean& mean) {
  const Extent e = level_extent(level0, level), fe = level_extent(level0, level - 1);
  std::vector<T> out(static_cast<std::size_t>(e.width) * e.height);
  tbb::parallel_for(tbb::blocked_range<int>(0, e.height), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j)
      for (int i = 0; i < e.width; ++i) {
        const Span cx = child_span(level0.width, level, i), cy = child_span(level0.height, level, j);
        const auto children = [&](const auto& add) {
          for (int y = cy.begin; y < cy.end; ++y)
            for (int x = cx.begin; x < cx.end; ++x)
              add(static_cast<double>(level0_span(level0.width, level - 1, x).size()) *
                      level0_span(level0.height, level - 1, y).size(),
                  fine[static_cast<std::size_t>(y) * fe.width + x]);
        };
        out[static_cast<std::size_t>(j) * e.width + i] = mean(children);
      }
  });
  return out;
}

std::vector<ParamTexel> params_from_below(Extent level0, int level, const std::vector<ParamTexel>& fine) {
  return level_from_below(level0, level, fine, [](const auto& children) {
    double total = 0, m = 0, rough = 0;
    glm::dvec3 c(0), n(0);
    children([&](double w, const ParamTexel& t) {
      total += w;
      c += w * glm::dvec3(t.base_color);
      m += w * t.metallic;
      rough += w * t.roughness;
      n += w * glm::dvec3(t.normal);
    });
    return ParamTexel{glm::vec3(c / total), static_cast<float>(m / total), static_cast<float>(rough / total),
                      glm::vec3(n / total)};
  });
}

// The specular layer's means, as params_from_below takes the parameters'.
std::vector<ParamSpecular> specular_from_below(Extent level0, int level, const std::vector<ParamSpecular>& fine) {
  return level_from_below(level0, level, fine, [](const auto& children) {
    double total = 0, s = 0;
    glm::dvec3 c(0);
    children([&](double w, const ParamSpecular& t) {
      total += w;
      s += w * t.specular;
      c += w * glm::dvec3(t.color);
    });
    return ParamSpecular{static_cast<float>(s / total), glm::vec3(c / total)};
  });
}

// The transmission's means, as params_from_below takes the parameters'.
std::vector<float> transmission_from_below(Extent level0, int level, const std::vector<float>& fine) {
  return level_from_below(level0, level, fine, [](const auto& children) {
    double total = 0, t = 0;
    children([&](double w, float x) {
      total += w;
      t += w * x;
    });
    return static_cast<float>(t / total);
  });
}

// The diffuse transmission's means (diffuse_transmission_mean), weighted as params_from_below weights
// the parameters.
std::vector<DiffuseTransmissionLayer> diffuse_transmission_from_below(Extent level0, int level,
                                                                      const std::vector<DiffuseTransmissionLayer>& fine) {
  return level_from_below(level0, level, fine, [](const auto& children) {
    double total = 0, share = 0;
    glm::dvec3 color(0);
    children([&](double w, const DiffuseTransmissionLayer& d) {
      total += w;
      share += w * d.share;
      color += (w * d.share) * glm::dvec3(d.color);
    });
    return diffuse_transmission_mean(total, share, color);
  });
}

// The clear coat's means, as params_from_below takes the parameters'.
std::vector<ParamCoat> coat_from_below(Extent level0, int level, const std::vector<ParamCoat>& fine) {
  return level_from_below(level0, level, fine, [](const auto& children) {
    double total = 0, c = 0, rough = 0;
    glm::dvec3 n(0);
    children([&](double w, const ParamCoat& t) {
      total += w;
      c += w * t.clearcoat;
      rough += w * t.roughness;
      n += w * glm::dvec3(t.normal);
    });
    return ParamCoat{static_cast<float>(c / total), static_cast<float>(rough / total), glm::vec3(n / total)};
  });
}

}  // namespace

std::vector<SheenLayer> sheen_from_below(Extent level0, int level, const std::vector<SheenLayer>& fine) {
  return level_from_below(level0, level, fine, [](const auto& children) {
    double total = 0, rough = 0;
    glm::dvec3 c(0);
    children([&](double w, const SheenLayer& t) {
      total += w;
      c += w * glm::dvec3(t.color);
      rough += w * t.roughness;
    });
    return SheenLayer{glm::vec3(c / total), static_cast<float>(rough / total)};
  });
}

std::vector<AnisotropyLayer> anisotropy_from_below(Extent level0, int level, const std::vector<AnisotropyLayer>& fine) {
  return level_from_below(level0, level, fine, [](const auto& children) {
    double total = 0;
    glm::dvec2 v(0.0);
    children([&](double w, const AnisotropyLayer& t) {
      total += w;
      v += w * axial_anisotropy(t);
    });
    return from_axial_anisotropy(v / total);
  });
}

ParamPyramid ParamPyramid::build(const MaterialTexels& m) {
  ParamPyramid p = level0_only(m);
  p.build_coarse_levels();
  return p;
}

ParamPyramid ParamPyramid::level0_only(const MaterialTexels& m) {
  ParamPyramid p;
  p.level0_ = {m.width, m.height};
  if (level_count(p.level0_) == 0) return p;
  // Level 0 is the texels: 512 MB at 4096², in huge pages and filled in parallel.
  std::vector<ParamTexel> base;
  assign_huge(base, m.size(), ParamTexel{});
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.size(), 1 << 16), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) base[k] = {m.base_color[k], m.metallic[k], m.roughness[k], m.normal[k]};
  });
  p.levels_.push_back(std::move(base));
  p.ior_ = m.ior;
  if (!m.specular.empty() || !m.specular_color.empty() || m.specular_factor != 1.0f ||
      m.specular_color_factor != glm::vec3(1.0f)) {
    std::vector<ParamSpecular> spec(m.size());
    for (std::size_t k = 0; k < m.size(); ++k) {
      const SpecularLayer l = m.specular_layer(k);
      spec[k] = {l.specular, l.color};
    }
    p.specular_.push_back(std::move(spec));
  }
  if (m.has_coat()) {
    std::vector<ParamCoat> coat(m.size());
    for (std::size_t k = 0; k < m.size(); ++k) {
      const CoatLayer c = m.coat_layer(k);
      coat[k] = {c.weight, c.roughness, c.normal};
    }
    p.coat_.push_back(std::move(coat));
  }
  if (m.has_sheen()) p.sheen_.push_back(sheen_level0(m));
  if (m.has_anisotropy()) {
    std::vector<AnisotropyLayer> aniso(m.size());
    for (std::size_t k = 0; k < m.size(); ++k) aniso[k] = m.anisotropy_layer(k);
    p.anisotropy_.push_back(std::move(aniso));
  }
  if (m.has_transmission()) {
    std::vector<float> transmission(m.size());
    for (std::size_t k = 0; k < m.size(); ++k) transmission[k] = m.transmission_at(k);
    p.transmission_.push_back(std::move(transmission));
  }
  if (m.has_diffuse_transmission()) {
    std::vector<DiffuseTransmissionLayer> d(m.size());
    for (std::size_t k = 0; k < m.size(); ++k) d[k] = m.diffuse_transmission_layer(k);
    p.diffuse_transmission_.push_back(std::move(d));
  }
  return p;
}

void ParamPyramid::build_coarse_levels() {
  for (int level = levels(); level > 0 && level < level_count(level0_); ++level) {
    levels_.push_back(params_from_below(level0_, level, levels_.back()));
    if (!specular_.empty()) specular_.push_back(specular_from_below(level0_, level, specular_.back()));
    if (!coat_.empty()) coat_.push_back(coat_from_below(level0_, level, coat_.back()));
    if (!sheen_.empty()) sheen_.push_back(sheen_from_below(level0_, level, sheen_.back()));
    if (!anisotropy_.empty()) anisotropy_.push_back(anisotropy_from_below(level0_, level, anisotropy_.back()));
    if (!transmission_.empty()) transmission_.push_back(transmission_from_below(level0_, level, transmission_.back()));
    if (!diffuse_transmission_.empty())
      diffuse_transmission_.push_back(diffuse_transmission_from_below(level0_, level, diffuse_transmission_.back()));
  }
}

MaterialTexels ParamPyramid::level0_texels() const {
  MaterialTexels m(level0_.width, level0_.height);
  if (levels_.empty()) return m;
  const std::vector<ParamTexel>& base = levels_.front();
  for (std::size_t k = 0; k < base.size(); ++k) {
    const ParamTexel& t = base[k];
    m.base_color[k] = t.base_color, m.metallic[k] = t.metallic;
    m.roughness[k] = t.roughness, m.normal[k] = t.normal;
  }
  m.ior = ior_;
  if (!specular_.empty()) {
    m.specular.resize(base.size());
    m.specular_color.resize(base.size());
    for (std::size_t k = 0; k < base.size(); ++k)
      m.specular[k] = specular_.front()[k].specular, m.specular_color[k] = specular_.front()[k].color;
  }
  if (!coat_.empty()) {
    // Every texel's own coat; the factor only says that the material has one (coat_layer reads the
    // texels').
    m.clearcoat_factor = 1.0f;
    m.clearcoat.resize(base.size());
    m.clearcoat_roughness.resize(base.size());
    m.clearcoat_normal.resize(base.size());
    for (std::size_t k = 0; k < base.size(); ++k) {
      const ParamCoat& c = coat_.front()[k];
      m.clearcoat[k] = c.clearcoat, m.clearcoat_roughness[k] = c.roughness, m.clearcoat_normal[k] = c.normal;
    }
  }
  if (!sheen_.empty()) {
    // Every texel's own sheen; the factor only says that the material has one (sheen_layer reads the
    // texels').
    m.sheen_color_factor = glm::vec3(1.0f);
    m.sheen_roughness_factor = 1.0f;
    m.sheen_color.resize(base.size());
    m.sheen_roughness.resize(base.size());
    for (std::size_t k = 0; k < base.size(); ++k)
      m.sheen_color[k] = sheen_.front()[k].color, m.sheen_roughness[k] = sheen_.front()[k].roughness;
  }
  if (!anisotropy_.empty()) {
    // Every texel's own; the factor only says that the material has one (anisotropy_layer reads the
    // texels').
    m.anisotropy_factor = 1.0f;
    m.anisotropy.resize(base.size());
    m.anisotropy_direction.resize(base.size());
    for (std::size_t k = 0; k < base.size(); ++k)
      m.anisotropy[k] = anisotropy_.front()[k].strength, m.anisotropy_direction[k] = anisotropy_.front()[k].direction;
  }
  if (!transmission_.empty()) {
    // Every texel's own; the factor only says that the material transmits (transmission_at reads the
    // texels').
    m.transmission_factor = 1.0f;
    m.transmission = transmission_.front();
  }
  if (!diffuse_transmission_.empty()) {
    // Every texel's own; the factors only say that the material has one (diffuse_transmission_layer reads
    // the texels').
    m.diffuse_transmission_factor = 1.0f;
    m.diffuse_transmission.resize(base.size());
    m.diffuse_transmission_color.resize(base.size());
    for (std::size_t k = 0; k < base.size(); ++k)
      m.diffuse_transmission[k] = diffuse_transmission_.front()[k].share,
      m.diffuse_transmission_color[k] = diffuse_transmission_.front()[k].color;
  }
  return m;
}

ParamPyramid ParamPyramid::from_levels(Extent level0, std::vector<std::vector<ParamTexel>> levels,
                                       std::vector<std::vector<ParamSpecular>> specular, float ior,
                                       std::vector<std::vector<ParamCoat>> coat,
                                       std::vector<std::vector<SheenLayer>> sheen,
                                       std::vector<std::vector<AnisotropyLayer>> anisotropy,
                                       std::vector<std::vector<float>> transmission,
                                       std::vector<std::vector<DiffuseTransmissionLayer>> diffuse_transmission) {
  if (static_cast<int>(levels.size()) != level_count(level0))
    throw Error("parameter pyramid: " + std::to_string(levels.size()) + " levels for a " +
                std::to_string(level0.width) + "x" + std::to_string(level0.height) + " level 0 (expected " +
                std::to_string(level_count(level0)) + ")");
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const Extent e = level_extent(level0, static_cast<int>(l));
    if (levels[l].size() != static_cast<std::size_t>(e.width) * e.height)
      throw Error("parameter pyramid: level " + std::to_string(l) + " has the wrong size");
    if (!specular.empty() && (specular.size() != levels.size() || specular[l].size() != levels[l].size()))
      throw Error("parameter pyramid: the specular layer's level " + std::to_string(l) + " has the wrong size");
    if (!coat.empty() && (coat.size() != levels.size() || coat[l].size() != levels[l].size()))
      throw Error("parameter pyramid: the coat's level " + std::to_string(l) + " has the wrong size");
    if (!sheen.empty() && (sheen.size() != levels.size() || sheen[l].size() != levels[l].size()))
      throw Error("parameter pyramid: the sheen's level " + std::to_string(l) + " has the wrong size");
    if (!anisotropy.empty() && (anisotropy.size() != levels.size() || anisotropy[l].size() != levels[l].size()))
      throw Error("parameter pyramid: the anisotropy's level " + std::to_string(l) + " has the wrong size");
    if (!transmission.empty() && (transmission.size() != levels.size() || transmission[l].size() != levels[l].size()))
      throw Error("parameter pyramid: the transmission's level " + std::to_string(l) + " has the wrong size");
    if (!diffuse_transmission.empty() &&
        (diffuse_transmission.size() != levels.size() || diffuse_transmission[l].size() != levels[l].size()))
      throw Error("parameter pyramid: the diffuse transmission's level " + std::to_string(l) + " has the wrong size");
  }
  ParamPyramid p;
  p.level0_ = level0;
  p.levels_ = std::move(levels);
  p.specular_ = std::move(specular);
  p.coat_ = std::move(coat);
  p.sheen_ = std::move(sheen);
  p.anisotropy_ = std::move(anisotropy);
  p.transmission_ = std::move(transmission);
  p.diffuse_transmission_ = std::move(diffuse_transmission);
  p.ior_ = ior;
  return p;
}

}  // namespace svbrdf
