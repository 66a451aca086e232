// How much memory Lueur may plan to use, so that work too big for the machine is refused up front with a clear
// message instead of ending in an out-of-memory kill. Depends on the standard library only.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace lueur {

struct MemoryBudget {
  uint64_t bytes = 0;
  std::string source;  ///< where the figure comes from, for messages: "MemAvailable", "cgroup limit", ...
};

/// The least of: MemAvailable from /proc/meminfo, what the process's cgroup (v1 or v2) still allows, the
/// address-space rlimit, and LUEUR_MEMORY_LIMIT_MB when set (a cap a user or test may impose). Throws
/// std::invalid_argument when LUEUR_MEMORY_LIMIT_MB is not a positive number.
MemoryBudget available_memory();

/// MemAvailable in bytes from the text of /proc/meminfo; nullopt when absent or malformed.
std::optional<uint64_t> parse_meminfo_available(std::string_view meminfo);

/// "512 KiB", "3.2 GiB": a byte count for messages.
std::string format_bytes(uint64_t bytes);

/// Empties `array` and frees its storage (assigning {} to a vector would keep it: that picks the initializer-list
/// assignment, which only clears).
template <typename Array>
void free_array(Array& array) {
  Array().swap(array);
}

/// Makes the allocator map every array of 4 MiB or more on its own and unmap it when freed, rather than keep freed
/// ones for reuse (glibc raises its threshold as large blocks are freed, up to 32 MiB, and then holds such blocks):
/// the stages of a large load free hundreds of megabytes that would otherwise add to the next stage's peak. Called
/// once by the programs at start.
void map_large_arrays_alone();

/// Hands the memory that freed arrays left in the allocator's arenas back to the system, so that the next stage of a
/// large load starts from what is really in use (glibc keeps freed blocks below its mmap threshold resident).
void release_free_memory();

/// The most memory this process has held resident so far (VmHWM in /proc/self/status); 0 where it cannot be read.
uint64_t peak_resident_bytes();

}  // namespace lueur
