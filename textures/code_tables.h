#pragma once
// Private to textures/ (color.cpp): a colour transform's output for every value an 8- or 16-bit code
// decodes to, channel by channel, so that texels read from integer files (PNG, JPEG) take a lookup
// instead of the transform's arithmetic. The sRGB decode is a pow per channel (OCIO's exact one:
// color.cpp keeps OpenColorIO's fast pow off), which took as much CPU time as libpng's unfiltering of
// all three files of a 4096² material; a table of 65536 codes holds every value a 16-bit file gives.
// Exact, not an approximation: a table entry is the transform's own output for that input, taken
// only where the texel's float is bit for bit the table's input for its code, and only for a
// transform without channel crosstalk (OpenColorIO's hasChannelCrosstalk), where a channel's output
// depends on that channel alone. Every other texel (a half or float file's, a value a factor
// scaled) goes through the transform as before.
#include <OpenColorIO/OpenColorIO.h>

#include <array>
#include <cstddef>
#include <vector>

namespace svbrdf {

// The float each code of `bits` bits (8 or 16) reads as: OpenImageIO's conversion to [0, 1], the one
// read_image applies to a file's stored values. 256 or 65536 values, made once.
const std::vector<float>& code_values(int bits);

class CodeTables {
 public:
  // The tables of `cpu`, a float-to-float processor; none when it has channel crosstalk.
  explicit CodeTables(const OCIO_NAMESPACE::ConstCPUProcessorRcPtr& cpu);
  bool empty() const { return tables_.empty(); }
  // Channels 0..2 of `n` pixels, `stride` floats apart from `first` on, through the transform, in
  // place: bit for bit what `cpu` gives them. Not empty().
  void apply(float* first, std::size_t n, std::size_t stride) const;

  // One code width: the float each code decodes to (code_values) and the transform's output for it
  // in each channel.
  struct Table {
    int max_code = 0;
    std::vector<float> in;
    std::array<std::vector<float>, 3> out;
  };
  // The table of `bits`-bit codes (8 or 16), for a decoder that reads the codes themselves. Not empty().
  const Table& codes(int bits) const { return tables_[bits == 16 ? 0 : 1]; }

 private:
  bool found(float v, int channel, float& out) const;
  OCIO_NAMESPACE::ConstCPUProcessorRcPtr cpu_;
  std::vector<Table> tables_;  // 16-bit, then 8-bit; empty: every texel through cpu_
};

}  // namespace svbrdf
