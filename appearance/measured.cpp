#include "appearance/measured.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <span>
#include <iterator>

#include "appearance/sampling.h"
#include "appearance/shading.h"
#include "base/atomic_file.h"
#include "base/error.h"

namespace svbrdf {
namespace {

static_assert(std::endian::native == std::endian::little, "the MERL layout is little-endian");

constexpr double kHalfPi = 0.5 * kPiD;
constexpr std::size_t kHeaderBytes = 3 * sizeof(std::int32_t);
constexpr std::size_t kDataBytes = 3 * static_cast<std::size_t>(MerlTable::kCells) * sizeof(double);

int clamp_index(double x, int n) { return std::clamp(static_cast<int>(std::floor(x)), 0, n - 1); }

}  // namespace

MerlTable::MerlTable() : f_(3 * static_cast<std::size_t>(kCells), 0.0f) {}

int MerlTable::cell_of(const glm::vec3& wi_f, const glm::vec3& wo_f) {
  const glm::dvec3 wi(wi_f), wo(wo_f);
  const glm::dvec3 h = glm::normalize(wi + wo);
  // d = wi rotated by −φh about z, then by −θh about y (Rusinkiewicz 1998), with the sines and
  // cosines of φh and θh read off h itself rather than through trigonometric calls.
  const double st = std::sqrt(h.x * h.x + h.y * h.y), ct = h.z;
  const double theta_h = std::atan2(st, ct);
  const double cp = st > 0 ? h.x / st : 1.0, sp = st > 0 ? h.y / st : 0.0;
  const glm::dvec3 a(wi.x * cp + wi.y * sp, -wi.x * sp + wi.y * cp, wi.z);
  const glm::dvec3 d(a.x * ct - a.z * st, a.y, a.x * st + a.z * ct);
  const double theta_d = std::atan2(std::sqrt(d.x * d.x + d.y * d.y), d.z);
  double phi_d = std::atan2(d.y, d.x);
  if (phi_d < 0) phi_d += kPiD;  // the reciprocity fold φd ~ φd + π
  const int ih = theta_h <= 0 ? 0 : clamp_index(std::sqrt(theta_h / kHalfPi) * kThetaH, kThetaH);
  const int id = clamp_index(theta_d / kHalfPi * kThetaD, kThetaD);
  const int ip = clamp_index(phi_d / kPiD * kPhiD, kPhiD);
  return cell(ih, id, ip);
}

void MerlTable::center_directions(int theta_h, int theta_d, int phi_d, glm::vec3& wi, glm::vec3& wo) {
  const double u = (theta_h + 0.5) / kThetaH;
  const double th = u * u * kHalfPi;
  const double td = (theta_d + 0.5) / kThetaD * kHalfPi;
  const double pd = (phi_d + 0.5) / kPhiD * kPiD;
  const glm::dvec3 d(std::sin(td) * std::cos(pd), std::sin(td) * std::sin(pd), std::cos(td));
  const double ct = std::cos(th), st = std::sin(th);
  // R_y(θh): (x, y, z) → (x cos + z sin, y, −x sin + z cos); wo is d mirrored about the half vector.
  wi = glm::vec3(glm::normalize(glm::dvec3(d.x * ct + d.z * st, d.y, -d.x * st + d.z * ct)));
  wo = glm::vec3(glm::normalize(glm::dvec3(-d.x * ct + d.z * st, -d.y, d.x * st + d.z * ct)));
}

Rgb MerlTable::at(int c) const {
  const auto i = 3 * static_cast<std::size_t>(c);
  return {f_[i], f_[i + 1], f_[i + 2]};
}

void MerlTable::set(int c, const Rgb& f) {
  const auto i = 3 * static_cast<std::size_t>(c);
  f_[i] = f.x;
  f_[i + 1] = f.y;
  f_[i + 2] = f.z;
}

Rgb MerlTable::lookup(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  return at(cell_of(wi, wo));
}

MerlTable MerlTable::read(const std::filesystem::path& path) {
  const std::string where = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(where, "cannot open the measured BRDF file");
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw input_error(where, "read error");
  if (bytes.size() < kHeaderBytes)
    throw input_error(where, "truncated MERL file: " + std::to_string(bytes.size()) + " bytes, no complete header");
  std::int32_t dims[3];
  std::memcpy(dims, bytes.data(), kHeaderBytes);
  if (dims[0] != kThetaH || dims[1] != kThetaD || dims[2] != kPhiD)
    throw input_error(where, "not a MERL table: dimensions " + std::to_string(dims[0]) + " " + std::to_string(dims[1]) +
                                 " " + std::to_string(dims[2]) + ", expected 90 90 180");
  const std::size_t expected = kHeaderBytes + kDataBytes;
  if (bytes.size() < expected)
    throw input_error(where, "truncated MERL file: " + std::to_string(bytes.size()) + " bytes, expected " +
                                 std::to_string(expected));
  if (bytes.size() > expected)
    throw input_error(where, "MERL file has " + std::to_string(bytes.size() - expected) + " unexpected trailing bytes");
  MerlTable t;
  const char* p = bytes.data() + kHeaderBytes;
  for (std::size_t i = 0; i < 3 * static_cast<std::size_t>(kCells); ++i) {
    double v;
    std::memcpy(&v, p + i * sizeof(double), sizeof(double));
    if (!std::isfinite(v)) throw input_error(where, "value " + std::to_string(i) + " is not a finite number");
    const std::size_t channel = i / static_cast<std::size_t>(kCells), cell = i % static_cast<std::size_t>(kCells);
    t.f_[3 * cell + channel] = v < 0 ? 0.0f : static_cast<float>(v * kScale[channel]);  // negative: not measured
  }
  return t;
}

void MerlTable::write(const std::filesystem::path& path) const {
  std::vector<char> bytes(kHeaderBytes + kDataBytes);
  const std::int32_t dims[3] = {kThetaH, kThetaD, kPhiD};
  std::memcpy(bytes.data(), dims, kHeaderBytes);
  char* p = bytes.data() + kHeaderBytes;
  for (std::size_t i = 0; i < f_.size(); ++i) {
    const std::size_t channel = i / static_cast<std::size_t>(kCells), cell = i % static_cast<std::size_t>(kCells);
    const double v = static_cast<double>(f_[3 * cell + channel]) / kScale[channel];
    std::memcpy(p + i * sizeof(double), &v, sizeof(double));
  }
  write_bytes_atomically(path, std::as_bytes(std::span(bytes)));
}

MerlTable MerlTable::tabulate(const Bsdf& bsdf) {
  MerlTable t;
  glm::vec3 wi, wo;
  for (int ih = 0; ih < kThetaH; ++ih)
    for (int id = 0; id < kThetaD; ++id)
      for (int ip = 0; ip < kPhiD; ++ip) {
        center_directions(ih, id, ip, wi, wo);
        t.set(cell(ih, id, ip), bsdf.eval(wi, wo));
      }
  return t;
}

Measured::Measured(std::shared_ptr<const MerlTable> table) : table_(std::move(table)) {}

Rgb Measured::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  return 0.5f * (table_->lookup(wi, wo) + table_->lookup(wo, wi));
}

BsdfSample Measured::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0) return {};
  const glm::vec3 wi = sample_cosine_hemisphere({u.y, u.z});
  if (wi.z <= 0) return {};
  return finite_sample(wi, wi.z * kInvPi, eval(wi, wo));
}

float Measured::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0f;
  return wi.z * kInvPi;
}

}  // namespace svbrdf
