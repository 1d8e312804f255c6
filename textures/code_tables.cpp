#include "textures/code_tables.h"

#include <OpenImageIO/imageio.h>

#include <bit>
#include <cstdint>
#include <limits>

namespace svbrdf {

namespace OCIO = OCIO_NAMESPACE;

namespace {

// Applies `cpu` to packed RGB floats.
void apply_packed(const OCIO::ConstCPUProcessorRcPtr& cpu, float* rgb, std::size_t n) {
  if (n == 0) return;
  OCIO::PackedImageDesc desc(rgb, long(n), 1, OCIO::CHANNEL_ORDERING_RGB, OCIO::BIT_DEPTH_F32, sizeof(float),
                             3 * sizeof(float), std::ptrdiff_t(3 * sizeof(float) * n));
  cpu->apply(desc);
}

}  // namespace

const std::vector<float>& code_values(int bits) {
  const auto make = [](auto code) {
    using Code = decltype(code);
    const std::size_t n = std::size_t(std::numeric_limits<Code>::max()) + 1;
    std::vector<Code> codes(n);
    for (std::size_t k = 0; k < n; ++k) codes[k] = Code(k);
    std::vector<float> values(n);
    OIIO::convert_pixel_values(OIIO::BaseTypeFromC<Code>::value, codes.data(), OIIO::TypeDesc::FLOAT, values.data(), int(n));
    return values;
  };
  static const std::vector<float> v8 = make(std::uint8_t{}), v16 = make(std::uint16_t{});
  return bits == 16 ? v16 : v8;
}

CodeTables::CodeTables(const OCIO::ConstCPUProcessorRcPtr& cpu) : cpu_(cpu) {
  if (cpu->hasChannelCrosstalk()) return;
  for (const int bits : {16, 8}) {
    Table t;
    t.in = code_values(bits);
    t.max_code = int(t.in.size()) - 1;
    const std::size_t n = t.in.size();
    std::vector<float> rgb(3 * n);
    for (std::size_t k = 0; k < n; ++k) rgb[3 * k] = rgb[3 * k + 1] = rgb[3 * k + 2] = t.in[k];
    apply_packed(cpu, rgb.data(), n);
    for (int c = 0; c < 3; ++c) {
      t.out[std::size_t(c)].resize(n);
      for (std::size_t k = 0; k < n; ++k) t.out[std::size_t(c)][k] = rgb[3 * k + std::size_t(c)];
    }
    tables_.push_back(std::move(t));
  }
}

bool CodeTables::found(float v, int channel, float& out) const {
  if (!(v >= 0.0f && v <= 1.0f)) return false;
  for (const Table& t : tables_) {
    const auto k = static_cast<std::size_t>(v * float(t.max_code) + 0.5f);
    if (std::bit_cast<std::uint32_t>(t.in[k]) != std::bit_cast<std::uint32_t>(v)) continue;
    out = t.out[std::size_t(channel)][k];
    return true;
  }
  return false;
}

void CodeTables::apply(float* first, std::size_t n, std::size_t stride) const {
  // Texels with a channel outside the tables, gathered and sent through the transform together.
  std::vector<float> rest;
  std::vector<std::size_t> rest_at;
  for (std::size_t p = 0; p < n; ++p) {
    float* px = first + p * stride;
    float out[3];
    if (found(px[0], 0, out[0]) && found(px[1], 1, out[1]) && found(px[2], 2, out[2])) {
      px[0] = out[0], px[1] = out[1], px[2] = out[2];
      continue;
    }
    rest.insert(rest.end(), px, px + 3);
    rest_at.push_back(p);
  }
  apply_packed(cpu_, rest.data(), rest_at.size());
  for (std::size_t r = 0; r < rest_at.size(); ++r)
    for (std::size_t c = 0; c < 3; ++c) first[rest_at[r] * stride + c] = rest[3 * r + c];
}

}  // namespace svbrdf
