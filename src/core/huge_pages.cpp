// Huge-page allocation: aligned_alloc on a 2 MiB boundary, then madvise(MADV_HUGEPAGE) where the kernel has it
// (Linux with transparent huge pages in "madvise" or "always" mode; elsewhere the advice is simply not given).
#include "core/huge_pages.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lueur {

void* allocate_huge_pages(std::size_t bytes) {
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  if (rounded < bytes) throw std::bad_alloc();
  void* p = std::aligned_alloc(kHugePageBytes, rounded);
  if (p == nullptr) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
  (void)madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure leaves ordinary pages
#endif
  return p;
}

void free_huge_pages(void* p) { std::free(p); }

}  // namespace lueur
