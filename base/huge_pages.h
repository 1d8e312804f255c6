#pragma once
// Large arrays in memory the kernel may back with transparent huge pages (madvise(2), MADV_HUGEPAGE:
// under the usual `madvise` setting of /sys/kernel/mm/transparent_hugepage/enabled Linux gives them
// only where asked). A 4096² material's texels are 512 MB, a level 1 of its lobes more; their first
// touch otherwise takes a page fault every 4 KiB, which costs more CPU time than filling them.
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace svbrdf {

// `v` made n copies of `value`, its memory advised for huge pages first (advice: the kernel may
// refuse it, and then `v` is as assign() makes it).
template <class T>
void assign_huge(std::vector<T>& v, std::size_t n, const T& value) {
  v.clear();
  v.reserve(n);
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t kHuge = std::uintptr_t(1) << 21;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(v.data()) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(v.data() + n) & ~(kHuge - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
  v.assign(n, value);
}

}  // namespace svbrdf
