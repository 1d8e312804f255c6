#include "mip/mip_file_checksum.h"

#include <OpenImageIO/hash.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace svbrdf::mip_file_checksum {

using namespace mip_file_channels;

void add_band(std::vector<std::uint64_t>& bands, std::span<const std::byte> name_ordered_pixels) {
  const auto f = OIIO::farmhash::Fingerprint128(reinterpret_cast<const char*>(name_ordered_pixels.data()),
                                                name_ordered_pixels.size());
  bands.push_back(OIIO::farmhash::Uint128Low64(f));
  bands.push_back(OIIO::farmhash::Uint128High64(f));
}

std::string level_checksum(const OIIO::ImageSpec& s, int max_lobes, float radial_inner, float radial_outer,
                           const std::vector<std::uint64_t>& bands) {
  std::string header = "level " + std::to_string(s.get_int_attribute("svbrdf:level", -1)) + " " +
                       std::to_string(s.width) + "x" + std::to_string(s.height) + " version " +
                       std::to_string(s.get_int_attribute("svbrdf:mip_version", 0)) + " slots " +
                       std::to_string(s.get_int_attribute("svbrdf:slots", -1)) + " max_lobes " +
                       std::to_string(max_lobes);
  std::uint32_t bits[2];
  std::memcpy(&bits[0], &radial_inner, 4);
  std::memcpy(&bits[1], &radial_outer, 4);
  header += " radial " + std::to_string(bits[0]) + " " + std::to_string(bits[1]);
  const float ior = s.get_float_attribute(kIor, 1.5f);
  std::memcpy(&bits[0], &ior, 4);
  header += " ior " + std::to_string(bits[0]);
  header += " tint " + std::to_string(s.get_int_attribute(kTint, 0));
  header += " coat_slots " + std::to_string(s.get_int_attribute(kCoatSlots, 0));
  // Channels in name order, as the pixels: OpenImageIO lists a file's channels in an order of its own.
  std::vector<std::string> channels;
  for (int c = 0; c < s.nchannels; ++c)
    channels.push_back(s.channelnames[static_cast<std::size_t>(c)] + ":" + std::string(s.channelformat(c).c_str()));
  std::sort(channels.begin(), channels.end());
  // Appended piece by piece: " " + a temporary trips GCC 12's -Wrestrict (a false positive).
  for (const std::string& c : channels) header.append(" ").append(c);
  for (const std::uint64_t b : bands) header.append(" ").append(std::to_string(b));
  const auto all = OIIO::farmhash::Fingerprint128(header.data(), header.size());
  char hex[33];
  std::snprintf(hex, sizeof hex, "%016llx%016llx", static_cast<unsigned long long>(OIIO::farmhash::Uint128High64(all)),
                static_cast<unsigned long long>(OIIO::farmhash::Uint128Low64(all)));
  return hex;
}

}  // namespace svbrdf::mip_file_checksum
