#include "appearance/sheen.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "appearance/shading.h"
#include "base/math.h"

namespace svbrdf {
namespace {

// Estevez & Kulla 2017, table 1: the fit of L(x) at α = 0 and at α = 1 (the extension's
// implementation notes carry the same numbers).
struct LambdaFit {
  double a, b, c, d, e;
};
constexpr LambdaFit kFitAlpha0{25.3245, 3.32435, 0.16801, -1.27393, -4.85967};
constexpr LambdaFit kFitAlpha1{21.5473, 3.82987, 0.19823, -1.97760, -4.32054};

LambdaFit lambda_fit(double alpha) {
  const double t = (1.0 - alpha) * (1.0 - alpha);  // weight of the α = 0 fit
  auto mix = [t](double at1, double at0) { return at1 + (at0 - at1) * t; };
  return {mix(kFitAlpha1.a, kFitAlpha0.a), mix(kFitAlpha1.b, kFitAlpha0.b), mix(kFitAlpha1.c, kFitAlpha0.c),
          mix(kFitAlpha1.d, kFitAlpha0.d), mix(kFitAlpha1.e, kFitAlpha0.e)};
}

double fit_l(const LambdaFit& p, double x) { return p.a / (1.0 + p.b * std::pow(x, p.c)) + p.d * x + p.e; }

double lambda_of(const LambdaFit& p, double cos_theta) {
  const double c = std::clamp(cos_theta, 0.0, 1.0);
  return c < 0.5 ? std::exp(fit_l(p, c)) : std::exp(2.0 * fit_l(p, 0.5) - fit_l(p, 1.0 - c));
}

// The albedo table. Rows: μ on u = √μ at the cell centres u_i = (i + ½)/32, so that rows crowd
// toward the horizon, where E changes fastest (E rises from 0.04 at μ = 1 to its maximum near
// μ = 0.005); a uniform μ grid interpolates 2.5× worse there. Columns: sheenRoughness s_j = j/31.
// Lookups outside the centres hold the edge value. Each entry is
//   E(μ, α) = 2 ∫_0^1 dcos θi ∫_0^π dφ f(wi, wo) cos θi        (f even in φ, wo in the xz-plane)
// by the midpoint rule, 96 × 48 nodes, in double; against 2048 × 1024 nodes it is within 2e-3 for
// μ < 0.1 and 1e-4 above (α ∈ {0.07, 0.3, 1}). The bilinear lookup then matches a brute-force
// quadrature of sheen_brdf to within 0.014 for μ < 0.01 and 0.0016 above (sheen_test.cpp).
constexpr int kRows = 32, kCols = 32, kNodesCos = 96, kNodesPhi = 48;

double table_mu(int row) {
  const double u = (row + 0.5) / kRows;
  return u * u;
}

struct AlbedoTable {
  std::array<float, kRows * kCols> e{};
  AlbedoTable() {
    std::array<double, kNodesCos> cos_i{}, sin_i{}, lambda_i{};
    std::array<double, kNodesPhi> cos_phi{}, sin_phi{};
    for (int k = 0; k < kNodesPhi; ++k) {
      const double phi = kPiD * (k + 0.5) / kNodesPhi;
      cos_phi[k] = std::cos(phi), sin_phi[k] = std::sin(phi);
    }
    for (int col = 0; col < kCols; ++col) {
      const double s = static_cast<double>(col) / (kCols - 1);
      const double alpha = std::max(s * s, static_cast<double>(kSheenMinAlpha));
      const LambdaFit fit = lambda_fit(alpha);
      for (int n = 0; n < kNodesCos; ++n) {
        cos_i[n] = (n + 0.5) / kNodesCos;
        sin_i[n] = std::sqrt(1.0 - cos_i[n] * cos_i[n]);
        lambda_i[n] = lambda_of(fit, cos_i[n]);  // Λ(ωi) depends on θi alone: once per column
      }
      for (int row = 0; row < kRows; ++row) {
        const double mu = table_mu(row), sin_o = std::sqrt(1.0 - mu * mu), lambda_o = lambda_of(fit, mu);
        double sum = 0;
        for (int n = 0; n < kNodesCos; ++n) {
          // f·cos θi = D(h) G2 / (4 cos θo): the cos θi of V cancels the cosine factor.
          const double g2 = 1.0 / (1.0 + lambda_i[n] + lambda_o);
          double inner = 0;
          for (int k = 0; k < kNodesPhi; ++k) {
            const double hx = sin_i[n] * cos_phi[k] + sin_o, hy = sin_i[n] * sin_phi[k], hz = cos_i[n] + mu;
            inner += sheen_distribution(hz / std::sqrt(hx * hx + hy * hy + hz * hz), alpha);
          }
          sum += inner * g2;
        }
        const double weight = 2.0 * (1.0 / kNodesCos) * (kPiD / kNodesPhi) / (4.0 * mu);
        e[static_cast<std::size_t>(row * kCols + col)] = static_cast<float>(sum * weight);
      }
    }
  }
};

const AlbedoTable& albedo_table() {
  static const AlbedoTable table;
  return table;
}

}  // namespace

float sheen_alpha(float sheen_roughness) { return std::max(sheen_roughness * sheen_roughness, kSheenMinAlpha); }

double sheen_distribution(double cos_h, double alpha) {
  const double sin2 = std::max(0.0, 1.0 - cos_h * cos_h);
  const double inv_alpha = 1.0 / alpha;
  return (2.0 + inv_alpha) * std::pow(sin2, 0.5 * inv_alpha) / (2.0 * kPiD);
}

double sheen_lambda(double cos_theta, double alpha) { return lambda_of(lambda_fit(alpha), cos_theta); }

SheenLambda::SheenLambda(double alpha) {
  const LambdaFit p = lambda_fit(alpha);
  a_ = p.a, b_ = p.b, c_ = p.c, d_ = p.d, e_ = p.e;
  l_half_ = fit_l(p, 0.5);
  af_ = float(a_), bf_ = float(b_), cf_ = float(c_), df_ = float(d_), ef_ = float(e_), l_half_f_ = float(l_half_);
}

float SheenLambda::operator()(float cos_theta) const {
  const float c = std::clamp(cos_theta, 0.0f, 1.0f);
  const auto l = [&](float x) { return af_ / (1.0f + bf_ * std::pow(x, cf_)) + df_ * x + ef_; };
  return c < 0.5f ? std::exp(l(c)) : std::exp(2.0f * l_half_f_ - l(1.0f - c));
}

double SheenLambda::operator()(double cos_theta) const {
  // lambda_of's expression, with L(0.5) from the constructor.
  const LambdaFit p{a_, b_, c_, d_, e_};
  const double c = std::clamp(cos_theta, 0.0, 1.0);
  return c < 0.5 ? std::exp(fit_l(p, c)) : std::exp(2.0 * l_half_ - fit_l(p, 1.0 - c));
}

double sheen_visibility(double cos_i, double cos_o, double alpha) {
  const LambdaFit fit = lambda_fit(alpha);
  return sheen_visibility_of(lambda_of(fit, cos_i), lambda_of(fit, cos_o), cos_i, cos_o);
}

double sheen_visibility_of(double lambda_i, double lambda_o, double cos_i, double cos_o) {
  return 1.0 / ((1.0 + lambda_i + lambda_o) * 4.0 * cos_i * cos_o);
}

Rgb sheen_brdf(const glm::vec3& wi, const glm::vec3& wo, const Rgb& sheen_color, float sheen_roughness) {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  const glm::vec3 h = wi + wo;  // both above the horizon, so h ≠ 0
  const double alpha = sheen_alpha(sheen_roughness);
  const double cos_h = static_cast<double>(h.z) / static_cast<double>(glm::length(h));
  const double f = sheen_distribution(cos_h, alpha) * sheen_visibility(wi.z, wo.z, alpha);
  return sheen_color * static_cast<float>(f);
}

float sheen_albedo(float mu, float sheen_roughness) {
  const AlbedoTable& t = albedo_table();
  const float x = std::clamp(std::sqrt(std::max(mu, 0.0f)) * kRows - 0.5f, 0.0f, kRows - 1.0f);
  const float y = std::clamp(sheen_roughness, 0.0f, 1.0f) * (kCols - 1);
  const int i = std::min(static_cast<int>(x), kRows - 2), j = std::min(static_cast<int>(y), kCols - 2);
  const float fx = x - i, fy = y - j;
  auto at = [&](int r, int c) { return t.e[static_cast<std::size_t>(r * kCols + c)]; };
  return (1 - fx) * ((1 - fy) * at(i, j) + fy * at(i, j + 1)) + fx * ((1 - fy) * at(i + 1, j) + fy * at(i + 1, j + 1));
}

float sheen_albedo_scaling(const glm::vec3& wi, const glm::vec3& wo, const Rgb& sheen_color, float sheen_roughness) {
  const float c = max_channel(sheen_color);
  const float e = std::max(sheen_albedo(wo.z, sheen_roughness), sheen_albedo(wi.z, sheen_roughness));
  return std::clamp(1.0f - c * e, 0.0f, 1.0f);
}

glm::vec3 sample_sheen(const glm::vec2& u) {
  // Uniform on the hemisphere: z uniform in [0, 1) (Archimedes), φ uniform.
  const float z = u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = kTwoPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

float sheen_pdf(const glm::vec3& wi, const glm::vec3& wo) {
  return wi.z > 0 && wo.z > 0 ? 0.5f * kInvPi : 0.0f;
}

Sheen::Sheen(const Rgb& sheen_color, float sheen_roughness) : color_(sheen_color), roughness_(sheen_roughness) {}

Rgb Sheen::eval(const glm::vec3& wi, const glm::vec3& wo) const { return sheen_brdf(wi, wo, color_, roughness_); }

float Sheen::scatter_probability(const glm::vec3& wo) const {
  return wo.z > 0 ? std::min(1.0f, max_channel(color_) * sheen_albedo(wo.z, roughness_)) : 0.0f;
}

BsdfSample Sheen::sample(const glm::vec3& wo, const SampleU& u) const {
  const float p = scatter_probability(wo);
  if (!(u.x < p)) return {};
  const glm::vec3 wi = sample_sheen({u.y, u.z});
  if (wi.z <= 0) return {};
  return finite_sample(wi, p * sheen_pdf(wi, wo), eval(wi, wo));
}

float Sheen::pdf(const glm::vec3& wi, const glm::vec3& wo) const { return scatter_probability(wo) * sheen_pdf(wi, wo); }

}  // namespace svbrdf
