#pragma once
// The scene's MIP data out of core (`svbrdf-render --texture-cache MB`): each material's MIP texture
// (mip/mip.h) as one record file of the texture cache (render/texture_tiles.h), read a tile at a time
// through its capped ImageCache, so the MIP data resident at once are bounded by the cap whatever the
// scene holds. Its records (mip/mip_records.h) decode to the in-memory pyramids' values bit for bit,
// so a render reads the same lobes from them as from memory.
//
// The file: one subimage a level, level L the pyramid's level L (its extent), kTileSide² texels a tile,
// each texel its record's 32-bit words; the records' layout, naming the key, in its description. It
// lives in the MIP cache's folder, named by the MIP cache key (render/mip_cache_key.h) of what it
// holds: the key itself for both pyramids, a key made from it for the parameter pyramid alone (what
// level0 and the parameter filters read, built without the BRDF pyramid's seconds); the MIP cache counts
// and evicts it as it does its entries (render/mip_cache.h). Written to a temporary, synced and renamed
// (base/atomic_file.h), and opened at once and kept open, so another render's eviction takes nothing
// from this one.
//
// Trust: at open the file must be a TIFF whose every level has the extent, the number of words and
// the tiles the layout in its description gives, and the description must name the key asked for and
// parse as a layout (levels as the extent gives, slots within kMaxLobes); a file that fails is one
// warning and is written again. What a corrupt tile can do: a tile that does not decompress is a read
// failure, which fails the render (exit 1, render/texture_tiles.h); one that decompresses to other
// words gives other parameters and lobes, never a read outside its record (the counts are held to the
// slots, mip_records.h decode_brdf) and never an index into memory (no decoded value is one).
#include <optional>
#include <string>

#include "mip/mip.h"
#include "render/texture_tiles.h"

namespace svbrdf {

// The side of a record file's tiles: records are up to a few hundred bytes, so that a thread's pinned
// tiles (TextureTiles::kPinnedTiles) stay a few megabytes.
inline constexpr int kRecordTileSide = 16;

// The record file's key for the MIP cache key `cache_key`: itself where the file holds the BRDF
// pyramid, else one made from it.
std::string mip_tiles_key(const std::string& cache_key, bool brdf);

// The texture read from the record file of `key` when one is there that holds what it must (see
// the header): one holding the BRDF pyramid when `brdf`. nullopt when there is none, or (with
// `warning` set) when the one there is refused.
std::optional<MipTexture> open_mip_tiles(TextureTiles& tiles, const std::string& key, bool brdf,
                                         WrapMode wrap_s, WrapMode wrap_t, std::string* warning);

// Writes `texture` (in memory, its parameter pyramid complete; its BRDF pyramid too when brdf is
// prepared) as the record file of `key` and returns the texture that reads it. Throws svbrdf::Error
// (environment) when the file can be neither written nor opened.
MipTexture to_mip_tiles(TextureTiles& tiles, const std::string& key, const MipTexture& texture,
                        WrapMode wrap_s, WrapMode wrap_t);

}  // namespace svbrdf
