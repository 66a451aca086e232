// Huge-page allocation: an anonymous mapping aligned on a 2 MiB boundary, then madvise(MADV_HUGEPAGE) where the
// kernel has it (Linux with transparent huge pages in "madvise" or "always" mode; elsewhere the advice is simply not
// given). Mapped directly rather than through malloc, so that freeing an array gives its memory back at once: the
// arrays of a large scene's build come and go, and memory the allocator kept would add to the load's peak.
#include "core/huge_pages.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <cstdint>

namespace lueur {
namespace {

std::size_t rounded_up(std::size_t bytes) {
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (rounded < bytes) throw std::bad_alloc();
  return rounded;
}

}  // namespace

#if defined(__linux__)

void* allocate_huge_pages(std::size_t bytes) {
  const std::size_t rounded = rounded_up(bytes);
  // Mapped with a huge page to spare, then trimmed to the aligned part.
  const std::size_t mapped = rounded + kHugePageBytes;
  if (mapped < rounded) throw std::bad_alloc();
  void* region = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (region == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(region);
  const std::uintptr_t aligned = (start + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (aligned > start) munmap(region, aligned - start);
  if (const std::size_t tail = start + mapped - (aligned + rounded); tail > 0)
    munmap(reinterpret_cast<void*>(aligned + rounded), tail);
  void* p = reinterpret_cast<void*>(aligned);
#if defined(MADV_HUGEPAGE)
  (void)madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure leaves ordinary pages
#endif
  return p;
}

void free_huge_pages(void* p, std::size_t bytes) {
  if (p != nullptr) munmap(p, rounded_up(bytes));
}

#else

void* allocate_huge_pages(std::size_t bytes) {
  void* p = std::aligned_alloc(kHugePageBytes, rounded_up(bytes));
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

void free_huge_pages(void* p, std::size_t) { std::free(p); }

#endif

}  // namespace lueur
