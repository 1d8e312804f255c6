#pragma once
// The temporary files a program has open right now (base/atomic_file.h makes them), kept where a
// signal handler can reach them: Ctrl-C or SIGTERM while an output is being written must not leave
// ".NAME.tmpPID.exr" behind (base/interrupt.h removes them before it exits). A handler may only call
// async-signal-safe functions, so the list is a fixed array of path buffers and atomic states — no
// allocation, no lock — and the removal is unlink(2).
//
// A file that cannot be registered (all slots taken, a path too long) is still written and removed
// as usual; only a signal in that window would leave it, and the next run removes a stale temporary
// whose process is gone (base/output_location.h).
#include <array>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace svbrdf {

namespace temp_files_detail {

enum State : int { kFree = 0, kFilling = 1, kReady = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[4096] = {};
};

// 64: a render stages at most six files at once (EXR, PNG, four AOVs); the rest is headroom for
// programs that write several in parallel. constinit: initialized before main, so a handler's first
// use runs no initialization guard (which is not async-signal-safe).
inline constinit std::array<Slot, 64> g_slots{};
inline std::array<Slot, 64>& slots() { return g_slots; }

}  // namespace temp_files_detail

// Registers `path` for removal by remove_registered_temp_files; returns its slot, or −1 when it
// could not be registered.
inline int register_temp_file(const std::filesystem::path& path) {
  using namespace temp_files_detail;
  const std::string& text = path.native();
  if (text.size() >= sizeof(Slot::path)) return -1;
  auto& all = slots();
  for (std::size_t i = 0; i < all.size(); ++i) {
    int expected = kFree;
    if (!all[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(all[i].path, text.c_str(), text.size() + 1);
    all[i].state.store(kReady);
    return static_cast<int>(i);
  }
  return -1;
}

inline void unregister_temp_file(int slot) {
  using namespace temp_files_detail;
  if (slot >= 0 && slot < static_cast<int>(slots().size())) slots()[static_cast<std::size_t>(slot)].state.store(kFree);
}

// Unlinks every registered file. Async-signal-safe: for signal handlers, right before _exit.
inline void remove_registered_temp_files() noexcept {
  using namespace temp_files_detail;
  for (Slot& s : slots())
    if (s.state.load() == kReady) ::unlink(s.path);
}

// A registration for a scope: the file's owner removes or renames it before the scope ends.
class RegisteredTempFile {
 public:
  explicit RegisteredTempFile(const std::filesystem::path& path) : slot_(register_temp_file(path)) {}
  ~RegisteredTempFile() { unregister_temp_file(slot_); }
  RegisteredTempFile(const RegisteredTempFile&) = delete;
  RegisteredTempFile& operator=(const RegisteredTempFile&) = delete;
  RegisteredTempFile(RegisteredTempFile&& o) noexcept : slot_(o.slot_) { o.slot_ = -1; }
  RegisteredTempFile& operator=(RegisteredTempFile&& o) noexcept {
    if (this != &o) {
      unregister_temp_file(slot_);
      slot_ = o.slot_;
      o.slot_ = -1;
    }
    return *this;
  }

 private:
  int slot_;
};

}  // namespace svbrdf
