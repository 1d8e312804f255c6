#pragma once
// A MIP texture's data (mip.h: the parameter pyramid, level 0 among it, and the BRDF pyramid) as fixed
// records of 32-bit words, one a texel of each level, for storage that is read a texel at a time (the
// renderer's out-of-core MIP data, render/mip_tiles.h). Decoding a record gives what the in-memory
// pyramids hold bit for bit: the parameters are their floats, and the lobes are stored in the MIP
// file's codes (stored_lobe.h, mip_file_channels.h), to which the BRDF build already rounds them.
//
// A record of level L, in words:
//   the parameters    8 floats (ParamTexel), then the specular layer's 4 (where the material's is
//                     not plain), the coat's 5, the sheen's 4, the anisotropy's 3, the
//                     transmission's 1 and the diffuse transmission's 4 (where it has them): every
//                     level;
//   the BRDF texel    for levels ≥ 1 of a texture with its BRDF pyramid: one word of counts (base
//                     lobes in bits 0–7, coat lobes in bits 8–15), S_L base slots, C_L coat slots and,
//                     where the level is corrected, the radial correction's 12 halves in 6 words.
// A lobe slot is the normal's direction code in one word and its other channels (the MIP file's of
// the level: mip_file_channels.h lobe_channels) as halves, two a word; a coat slot is the coat lobe's
// channels so (4 words). S_L is the most lobes a texel of the level keeps (BrdfLevel::slots), C_L the
// most coat lobes, as in the MIP file; the sheen means of levels ≥ 1 are the parameter pyramid's, as
// the MIP file stores them once.
//
// The layout (sizes, which layers, S_L and C_L, the radial grid) is a line of text that the storage
// keeps beside the records (describe, parse): parse checks it against the key it must name and
// against itself (levels as the extent gives, slots within kMaxLobes), and the record decoders clamp
// the counts to the slots, so a record that holds garbage gives garbage lobes, never a read outside it.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mip/brdf_pyramid.h"
#include "mip/param_pyramid.h"
#include "mip/pyramid_shape.h"
#include "mip/radial_correction.h"

namespace svbrdf {

struct MipRecordLayout {
  static constexpr int kParamWords = 8, kSpecularWords = 4, kCoatWords = 5, kSheenWords = 4, kAnisotropyWords = 3,
                       kTransmissionWords = 1, kDiffuseTransmissionWords = 4;
  static constexpr int kCoatLobeWords = 4;  // direction, then 5 halves
  static constexpr int kCorrectionWords = RadialGrid::kNodes / 2;

  Extent extent{};
  int levels = 0;
  bool brdf = false;      // levels ≥ 1 hold the BRDF pyramid's texels
  bool tint = false;      // the BRDF pyramid is tintable
  bool specular = false;  // the parameter pyramid holds the specular layer (not plain)
  bool coat = false, sheen = false, anisotropy = false, transmission = false, diffuse_transmission = false;
  float ior = 1.5f;
  int max_lobes = 1;
  float radial_inner = 0.0f, radial_outer = 0.0f;  // the radial grid (0: none)
  struct Level {
    int slots = 0, coat_slots = 0;
    // The lobes' layers (mip_file_channels.h LobeLayers), the correction.
    bool lobe_specular = false, lobe_tint = false, lobe_stretch = false, lobe_transmission = false,
         lobe_transmission90 = false, lobe_transmission_stretch = false, lobe_diffuse_transmission = false,
         lobe_diffuse_transmission90 = false, radial = false;
  };
  std::vector<Level> level;  // one a level
  // Per level, the roles of a lobe's half channels (mip_file_channels.h), made by of() and parse().
  std::vector<std::vector<std::uint8_t>> roles;

  // Of the pyramids `param` (complete) and, where not null, `brdf` (of the same level 0).
  static MipRecordLayout of(const ParamPyramid& param, const BrdfPyramid* brdf);

  int param_words() const {
    return kParamWords + (specular ? kSpecularWords : 0) + (coat ? kCoatWords : 0) +
           (sheen ? kSheenWords : 0) + (anisotropy ? kAnisotropyWords : 0) + (transmission ? kTransmissionWords : 0) +
           (diffuse_transmission ? kDiffuseTransmissionWords : 0);
  }
  int lobe_words(int l) const { return 1 + (int(roles[static_cast<std::size_t>(l)].size()) + 1) / 2; }
  int words(int l) const;
  RadialGrid radial_grid() const {
    return radial_inner > 0.0f ? RadialGrid::with_inner(radial_inner, radial_outer) : RadialGrid{};
  }

  // One line naming `key` and the layout; parse reads it back, nullopt (and `why`) when it names
  // another key or is not a layout this code writes.
  std::string describe(const std::string& key) const;
  static std::optional<MipRecordLayout> parse(const std::string& text, const std::string& key,
                                              std::string* why);

 private:
  void find_roles();
};

// Rows [row_begin, row_end) of level `l`'s records, each layout.words(l) words, into `out`.
void encode_records(const MipRecordLayout& layout, const ParamPyramid& param, const BrdfPyramid* brdf, int l,
                    int row_begin, int row_end, std::uint32_t* out);

// A record's parameters: the texel's, and its specular layer, coat, sheen, anisotropy, transmission and
// diffuse transmission where the layout has them (each left as it is where not).
void decode_params(const MipRecordLayout& layout, const std::uint32_t* record, ParamTexel& texel,
                   ParamSpecular* specular, ParamCoat* coat, SheenLayer* sheen, AnisotropyLayer* anisotropy = nullptr,
                   float* transmission = nullptr, DiffuseTransmissionLayer* diffuse_transmission = nullptr);
// A level-≥ 1 record's BRDF texel: its base lobes and coat lobes (at most the level's slots each), and its
// radial correction where the level has one (`corrected` says).
struct RecordTexel {
  int lobes = 0, coat_lobes = 0;
  bool corrected = false;
};
RecordTexel decode_brdf(const MipRecordLayout& layout, int l, const std::uint32_t* record, Lobe* lobes,
                        Lobe* coat_lobes, RadialCorrection& correction);

// Where a MipTexture's records live (render/mip_tiles.h: the texture cache's tiles): the record of
// texel (i, j) of level `level`, valid until the calling thread's next call. Thread-safe.
class MipRecordSource {
 public:
  virtual ~MipRecordSource() = default;
  virtual const std::uint32_t* record(int level, int i, int j) const = 0;
};

// A MipTexture's records (mip.h): their layout, where they are read from, and the radial grid.
struct MipRecords {
  MipRecordLayout layout;
  std::unique_ptr<const MipRecordSource> source;
  RadialGrid grid;
};

}  // namespace svbrdf
