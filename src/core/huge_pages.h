// An allocator that asks the kernel for transparent huge pages (2 MiB) for large arrays: a BVH of a million
// triangles is hundreds of 4 KiB pages per millisecond of build, and on virtual machines each first touch of a page
// is a costly fault. Huge pages also cut the TLB misses of incoherent traversal. Depends on the standard library.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

namespace lueur {

/// Arrays of at least this many bytes are allocated on 2 MiB boundaries and marked for huge pages.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

/// Allocates `bytes` (>= kHugePageBytes) 2 MiB-aligned, rounded up to whole huge pages, and advises the kernel to
/// back it with huge pages (where it cannot, the memory is ordinary). Throws std::bad_alloc.
void* allocate_huge_pages(std::size_t bytes);
/// Frees what allocate_huge_pages(bytes) gave, handing the memory back to the system at once.
void free_huge_pages(void* p, std::size_t bytes);

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}  // NOLINT: converting, as allocators must be

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugePageBytes) return static_cast<T*>(allocate_huge_pages(bytes));
    return static_cast<T*>(::operator new(bytes, std::align_val_t{alignof(T)}));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) >= kHugePageBytes)
      free_huge_pages(p, n * sizeof(T));
    else
      ::operator delete(p, std::align_val_t{alignof(T)});
  }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

/// A vector whose large buffers sit on huge pages.
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace lueur
