// SPDX-License-Identifier: GPL-3.0-or-later
// The program's operator new and delete, on mimalloc. mimalloc's own (libmimalloc's override, and
// mi_new) abort the process when memory runs out, where C++ throws std::bad_alloc: these throw, so
// an exhausted run ends as every failed run does, with one line, exit status 2 and no partial file.
#include <mimalloc.h>
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <new>
#include <optional>
#include <string>
#include <utility>

namespace {

void* allocate(std::size_t size) {
  if (void* p = mi_malloc(size)) return p;
  throw std::bad_alloc();
}
void* allocate(std::size_t size, std::align_val_t alignment) {
  if (void* p = mi_malloc_aligned(size, static_cast<std::size_t>(alignment))) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return mi_malloc(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return mi_malloc(size); }
void* operator new(std::size_t size, std::align_val_t alignment) { return allocate(size, alignment); }
void* operator new[](std::size_t size, std::align_val_t alignment) { return allocate(size, alignment); }
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return mi_malloc_aligned(size, static_cast<std::size_t>(alignment));
}
void* operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return mi_malloc_aligned(size, static_cast<std::size_t>(alignment));
}

void operator delete(void* p) noexcept { mi_free(p); }
void operator delete[](void* p) noexcept { mi_free(p); }
void operator delete(void* p, std::size_t) noexcept { mi_free(p); }
void operator delete[](void* p, std::size_t) noexcept { mi_free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { mi_free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { mi_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { mi_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { mi_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { mi_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { mi_free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { mi_free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { mi_free(p); }

// mimalloc's defaults suit a long-running server: memory freed goes back to the system after 25 ms,
// in 4 KiB pages. A design allocates and frees grids of the whole card round after round, and on a
// virtual machine every page faulted back in costs: here 13 % of a design's samples were the
// kernel's. 2 MiB pages (transparent huge pages, which mimalloc asks for) and memory kept took
// seedlike/sphere 1.91 -> 1.71 s, seedlike/torus 1.58 -> 1.35 s and res_dragon_full 4.46 -> 3.88 s
// (medians of 9, 5 and 5 runs, alternating) at the same peak memory. The environment's
// MIMALLOC_LARGE_OS_PAGES and MIMALLOC_ALLOW_DECOMMIT, where set, still decide.
// (mimalloc 2.1 calls handing memory back purging.)
//
// mimalloc maps its first segment while libstdc++ starts (for its exception pool), before these
// options are set, so without the 2 MiB page hint; the grids a design allocates first went there
// and were faulted in 4 KiB at a time, each fault costing here about 12 us, 3 ms a MiB (2 MiB
// pages: 0.1 to 1 ms a MiB). The mapping holding mimalloc's first block gets the hint too.
namespace {

// The start and end of the mapping of this process that holds `p`, from /proc/self/maps.
std::optional<std::pair<std::uintptr_t, std::uintptr_t>> mapping_of(const void* p) {
  const auto at = reinterpret_cast<std::uintptr_t>(p);
  std::ifstream maps("/proc/self/maps");
  std::uintptr_t start = 0, end = 0;
  char dash = 0;
  for (std::string rest; maps >> std::hex >> start >> dash >> end && std::getline(maps, rest);)
    if (start <= at && at < end) return std::pair{start, end};
  return std::nullopt;
}

[[maybe_unused]] const bool kAllocationOptions = [] {
  if (!std::getenv("MIMALLOC_LARGE_OS_PAGES")) {
    mi_option_enable(mi_option_large_os_pages);
    void* first = mi_malloc(1);
    if (const auto mapping = mapping_of(first))
      madvise(reinterpret_cast<void*>(mapping->first), mapping->second - mapping->first, MADV_HUGEPAGE);
    mi_free(first);
  }
#if MI_MALLOC_VERSION >= 210
  if (!std::getenv("MIMALLOC_PURGE_DELAY")) mi_option_set(mi_option_purge_delay, -1);
#else
  if (!std::getenv("MIMALLOC_ALLOW_DECOMMIT")) mi_option_disable(mi_option_allow_decommit);
#endif
  return true;
}();
}  // namespace
