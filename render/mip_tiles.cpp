#include "render/mip_tiles.h"

#include <memory>

#include "base/sha256.h"
#include "mip/mip_records.h"

namespace svbrdf {

namespace {

// A MipTexture's records from the texture cache's file `file`.
class TiledRecords final : public MipRecordSource {
 public:
  TiledRecords(const TextureTiles& tiles, int file) : tiles_(tiles), file_(file) {}
  const std::uint32_t* record(int level, int i, int j) const override {
    return tiles_.record(file_, level, i, j);
  }

 private:
  const TextureTiles& tiles_;
  int file_;
};

// The file's layout that `layout` gives: its levels' extents and words.
RecordLayout file_layout(const MipRecordLayout& layout, const std::string& key) {
  RecordLayout out;
  out.tile_side = kRecordTileSide;
  out.description = layout.describe(key);
  for (int l = 0; l < layout.levels; ++l) {
    const Extent e = level_extent(layout.extent, l);
    out.levels.push_back({e.width, e.height, layout.words(l)});
  }
  return out;
}

MipTexture reading(const TextureTiles& tiles, int file, const MipRecordLayout& layout, WrapMode wrap_s,
                   WrapMode wrap_t) {
  return MipTexture(layout, std::make_unique<TiledRecords>(tiles, file), wrap_s, wrap_t);
}

}  // namespace

std::string mip_tiles_key(const std::string& cache_key, bool brdf) {
  return brdf ? cache_key : to_hex(sha256("svbrdf mip records of the parameter pyramid|" + cache_key));
}

std::optional<MipTexture> open_mip_tiles(TextureTiles& tiles, const std::string& key, bool brdf,
                                         WrapMode wrap_s, WrapMode wrap_t, std::string* warning) {
  std::string why;
  const std::optional<RecordLayout> file = tiles.inspect_records(key, &why);
  std::optional<MipRecordLayout> layout;
  if (file) {
    layout = MipRecordLayout::parse(file->description, key, &why);
    if (layout && (*file != file_layout(*layout, key) || layout->brdf != brdf)) {
      why = "its levels are not laid out as its description says";
      layout.reset();
    }
    if (!layout) why = tiles.path_of(key).string() + ": " + why;
  }
  if (!layout) {
    if (warning && !why.empty())
      *warning = "the texture cache's file " + why + "; the material's MIP data are written again";
    return std::nullopt;
  }
  return reading(tiles, tiles.open_records(key, *file), *layout, wrap_s, wrap_t);
}

MipTexture to_mip_tiles(TextureTiles& tiles, const std::string& key, const MipTexture& texture,
                        WrapMode wrap_s, WrapMode wrap_t) {
  const MipRecordLayout layout = texture.record_layout();
  const int file = tiles.write_records(key, file_layout(layout, key),
                                       [&](int level, int begin, int end, std::uint32_t* out) {
                                         texture.encode_records(layout, level, begin, end, out);
                                       });
  return reading(tiles, file, layout, wrap_s, wrap_t);
}

}  // namespace svbrdf
