#include "mip/mip_file_checksum.h"

#include <OpenImageIO/hash.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "textures/exr_header.h"

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

void put_checksums(const std::filesystem::path& file, const std::vector<std::string>& checksums, const std::string& where) {
  const std::vector<ExrAttributeValue> values = find_exr_attribute(file, kChecksum, where);
  if (values.size() != checksums.size())
    throw Error(where + ": the written file has " + std::to_string(values.size()) + " levels, not " +
                    std::to_string(checksums.size()),
                Error::Kind::internal);
  const auto errno_text = [](int e) { return std::error_code(e, std::generic_category()).message(); };
  const int fd = ::open(file.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) throw environment_error(where, "cannot reopen the written file: " + errno_text(errno));
  std::string failed;
  for (std::size_t p = 0; p < checksums.size() && failed.empty(); ++p) {
    const ExrAttributeValue& v = values[p];
    std::string held(kChecksumPlaceholder.size(), '\0');
    if (v.size != held.size() || checksums[p].size() != held.size() ||
        ::pread(fd, held.data(), held.size(), off_t(v.offset)) != ssize_t(held.size()) || held != kChecksumPlaceholder) {
      ::close(fd);
      throw Error(where + ": level " + std::to_string(p) + "'s header holds no checksum placeholder", Error::Kind::internal);
    }
    const ssize_t wrote = ::pwrite(fd, checksums[p].data(), held.size(), off_t(v.offset));
    if (wrote != ssize_t(held.size()))
      failed = "cannot write level " + std::to_string(p) + "'s checksum: " + (wrote < 0 ? errno_text(errno) : "a short write");
  }
  if (::close(fd) != 0 && failed.empty()) failed = "cannot close the written file: " + errno_text(errno);
  if (!failed.empty()) throw environment_error(where, failed);
}

}  // namespace svbrdf::mip_file_checksum
