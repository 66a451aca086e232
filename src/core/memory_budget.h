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

}  // namespace lueur
