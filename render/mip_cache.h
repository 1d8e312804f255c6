#pragma once
// The MIP cache: a folder of finished MIP builds, one MIP file a build (mip/mip_file.h), named by the
// build's key (render/mip_cache_key.h) so that a render whose materials were built before reads them
// instead of building them again. It is an optimization: nothing it does may fail a render.
//
// Where: `svbrdf-render --mip-cache DIR`, else $SVBRDF_MIP_CACHE, else $XDG_CACHE_HOME/svbrdf/mip,
// else ~/.cache/svbrdf/mip (the XDG Base Directory Specification's per-user cache); `off` disables
// it. A folder that cannot be created or written is one warning, and the render goes on without it.
//
// An entry is never trusted: it carries its key (svbrdf:cache_key, checked before its pixels are
// read) and a checksum of every level (svbrdf:checksum). One that cannot be read, or holds another
// key, or fails its checksum, is one warning naming the file; the material is built and the entry
// replaced.
//
// Size: at most max_bytes of entries, the least recently used (by modification time, which a hit
// renews) removed first after each store. The texture cache's files in the folder
// (render/texture_tiles.h) count and go the same way; a render reads its own through links of its own,
// so removing them under it takes nothing from it.
//
// Concurrent renders may share a folder: an entry is written to a temporary beside it (the process
// id in its name, base/atomic_file.h) and renamed into place, so a reader sees a whole entry or none;
// an entry that vanishes (another render's eviction) is a miss, and a removal that finds nothing is
// no error. Thread-safe.
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "mip/mip.h"
#include "mip/mip_file.h"

namespace svbrdf {

// The tag of the links through which a render reads the texture cache's files (render/texture_tiles.h):
// ".KEY.heldPID.tx", removed by the eviction once that process is gone.
inline constexpr char kHeldTag[] = ".held";

class MipCache {
 public:
  static constexpr std::uint64_t kDefaultMegabytes = 4096;

  // The folder named by the environment as above; nullopt when none can be named (no HOME).
  static std::optional<std::filesystem::path> default_folder();

  MipCache(std::filesystem::path folder, std::uint64_t max_bytes);
  MipCache(const MipCache&) = delete;
  MipCache& operator=(const MipCache&) = delete;

  const std::filesystem::path& folder() const { return folder_; }
  std::filesystem::path entry_path(const std::string& key) const { return folder_ / (key + ".exr"); }

  // The entry of `key`, or nullopt: none (or it vanished), or a bad one (a warning). A good entry's
  // last use becomes now.
  std::optional<MipData> load(const std::string& key);
  // Writes `texture` (brdf and param prepared) as the entry of `key`, then evicts down to the size
  // limit. A failure is a warning.
  void store(const std::string& key, const MipTexture& texture);

  // Whether a store failed (said in a warning): a program whose work is to fill the cache fails.
  bool store_failed() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return unwritable_;
  }

  // The warnings so far, one line each, and forgets them.
  std::vector<std::string> take_warnings();

  // Removes the least recently used entries until the folder is within the size limit (store() does
  // after each entry; a writer of the texture cache's files after each of those). Removing a file
  // this process reads through its link (render/texture_tiles.h) leaves the render whole but the
  // next one cold: a warning, once, says the limit is below what the render uses.
  void evict();

 private:
  void warn(const std::string& line);

  std::filesystem::path folder_;
  std::uint64_t max_bytes_;
  std::mutex mutex_;  // guards the members below; entries are files, shared with other processes
  std::vector<std::string> warnings_;
  bool unwritable_ = false;  // a store failed for the folder's sake: later stores are skipped
  bool below_use_said_ = false;  // an eviction removed a file this process reads (said once)
};

}  // namespace svbrdf
