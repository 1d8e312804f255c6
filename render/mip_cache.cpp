#include "render/mip_cache.h"

#include <fcntl.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <utility>

#include "base/error.h"
#include "base/output_location.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

// An entry's file name: the key's 64 hexadecimal digits and ".exr", or ".tx" for a texture cache's
// file (render/texture_tiles.h), which the folder's size counts too.
bool is_entry_name(const std::string& name) {
  const bool exr = name.size() == 68 && name.compare(64, 4, ".exr") == 0;
  const bool tx = name.size() == 67 && name.compare(64, 3, ".tx") == 0;
  return (exr || tx) && name.find_first_not_of("0123456789abcdef") == 64;
}

// A temporary left by a writer that was killed (".KEY.tmpPID.exr" or ".tx" whose process is gone), or
// a texture cache file's link held by a render that was (".KEY.heldPID.tx", render/texture_tiles.h).
bool is_stale_temporary(const fs::path& folder, const std::string& name) {
  if (name.empty() || name[0] != '.') return false;
  const std::string key = name.substr(1, std::min<std::size_t>(64, name.size() - 1));
  return is_stale_temp_of(name, folder / (key + ".exr")) || is_stale_temp_of(name, folder / (key + ".tx")) ||
         is_stale_temp_of(name, folder / (key + ".tx"), kHeldTag);
}

std::string megabytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", double(bytes) / 1e6);
  return text;
}

}  // namespace

std::optional<fs::path> MipCache::default_folder() {
  const auto set = [](const char* name) -> const char* {
    const char* v = std::getenv(name);
    return v && *v ? v : nullptr;
  };
  if (const char* dir = set("SVBRDF_MIP_CACHE")) return fs::path(dir);
  // XDG Base Directory Specification: $XDG_CACHE_HOME must be absolute, else it is ignored.
  if (const char* xdg = set("XDG_CACHE_HOME"); xdg && xdg[0] == '/') return fs::path(xdg) / "svbrdf" / "mip";
  if (const char* home = set("HOME")) return fs::path(home) / ".cache" / "svbrdf" / "mip";
  return std::nullopt;
}

MipCache::MipCache(fs::path folder, std::uint64_t max_bytes) : folder_(std::move(folder)), max_bytes_(max_bytes) {}

void MipCache::warn(const std::string& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  warnings_.push_back(line);
}

std::vector<std::string> MipCache::take_warnings() {
  const std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(warnings_, {});
}

std::optional<MipData> MipCache::load(const std::string& key) {
  const fs::path path = entry_path(key);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;  // no entry (or the folder is not there)
  try {
    MipData data = read_mip_file(path, key);
    // Its last use, for the eviction; an entry that has just vanished is used all the same.
    ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0);
    return data;
  } catch (const std::exception& e) {
    // Evicted by another render while being read: a miss like any other.
    if (::stat(path.c_str(), &st) != 0) return std::nullopt;
    // svbrdf::Error names the file already; anything else (memory) is said with it.
    const std::string what = dynamic_cast<const Error*>(&e) ? e.what() : path.string() + ": " + e.what();
    warn("the MIP cache entry " + what + "; the material is built again and the entry replaced");
    return std::nullopt;
  }
}

void MipCache::store(const std::string& key, const MipTexture& texture) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (unwritable_) return;
  }
  try {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (ec) throw environment_error(folder_.string(), "cannot create the folder: " + ec.message());
    texture.write(entry_path(key), key);
  } catch (const std::exception& e) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (unwritable_) return;  // said once
      unwritable_ = true;
    }
    warn(std::string("the MIP cache cannot store a build (") + e.what() + "); the render goes on without storing");
    return;
  }
  evict();
}

void MipCache::evict() {
  struct Entry {
    fs::path path;
    std::uint64_t bytes;
    struct timespec used;
  };
  std::vector<Entry> entries;
  std::uint64_t total = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (is_stale_temporary(folder_, name)) {
      std::error_code rm;
      fs::remove(it->path(), rm);
      continue;
    }
    struct stat st {};
    if (!is_entry_name(name) || ::lstat(it->path().c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    entries.push_back({it->path(), std::uint64_t(st.st_size), st.st_mtim});
    total += std::uint64_t(st.st_size);
  }
  if (total <= max_bytes_) return;
  // Least recently used first; the newest (the entry just stored) last.
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.used.tv_sec != b.used.tv_sec ? a.used.tv_sec < b.used.tv_sec : a.used.tv_nsec < b.used.tv_nsec;
  });
  bool removed_in_use = false;
  for (const Entry& e : entries) {
    if (total <= max_bytes_) break;
    std::error_code rm;
    fs::remove(e.path, rm);  // gone already (another render's eviction): counted out all the same
    total -= e.bytes;
    removed_in_use = removed_in_use || fs::exists(process_path_for(e.path, kHeldTag), rm);
    if (&e == &entries.back())
      warn("the MIP cache entry " + e.path.string() + " (" + megabytes(e.bytes) + ") is larger than the cache's limit of " +
           megabytes(max_bytes_) + " (--mip-cache-size); it was not kept");
  }
  if (removed_in_use) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (std::exchange(below_use_said_, true)) return;
    }
    warn("the MIP cache's limit of " + megabytes(max_bytes_) + " (--mip-cache-size) is below the files this render "
         "uses: it removed some of them (the render still reads them), so the next render builds them again; a "
         "larger limit keeps them");
  }
}

}  // namespace svbrdf
