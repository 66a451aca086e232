// The memory budget: /proc/meminfo, the cgroup's limit, the address-space rlimit and an optional user cap.
#include "core/memory_budget.h"

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <sys/resource.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <unistd.h>

namespace lueur {
namespace {

std::optional<std::string> read_small_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::optional<uint64_t> parse_u64(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.remove_suffix(1);
  uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

/// Limit minus usage of one cgroup directory (v2 names, then v1 names); nullopt when it has no limit.
std::optional<uint64_t> cgroup_headroom(const std::string& dir) {
  for (const auto& [limit_name, usage_name] :
       {std::pair{"memory.max", "memory.current"}, std::pair{"memory.limit_in_bytes", "memory.usage_in_bytes"}}) {
    const std::optional<std::string> limit_text = read_small_file(dir + "/" + limit_name);
    if (!limit_text) continue;
    const std::optional<uint64_t> limit = parse_u64(*limit_text);      // "max" (v2 without a limit) does not parse
    if (!limit || *limit >= (uint64_t{1} << 62)) return std::nullopt;  // v1 writes "no limit" as about 2^63
    const std::optional<std::string> usage_text = read_small_file(dir + "/" + usage_name);
    const uint64_t usage = usage_text ? parse_u64(*usage_text).value_or(0) : 0;
    return *limit > usage ? *limit - usage : 0;
  }
  return std::nullopt;
}

/// The tightest headroom of the process's memory cgroup and its ancestors.
std::optional<uint64_t> cgroup_available() {
  const std::optional<std::string> self = read_small_file("/proc/self/cgroup");
  if (!self) return std::nullopt;
  std::optional<uint64_t> best;
  std::istringstream lines(*self);
  for (std::string line; std::getline(lines, line);) {
    // "0::/path" (v2) or "4:memory:/path" (v1)
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    std::string base;
    if (controllers.empty())
      base = "/sys/fs/cgroup";
    else if (controllers == "memory" || controllers.find("memory,") == 0 ||
             controllers.find(",memory") != std::string::npos)
      base = "/sys/fs/cgroup/memory";
    else
      continue;
    // The process's cgroup and each of its ancestors: a parent's limit binds too.
    std::string path = line.substr(second + 1);
    while (true) {
      std::string dir = base;
      if (path != "/") dir += path;
      if (const std::optional<uint64_t> headroom = cgroup_headroom(dir))
        best = best ? std::min(*best, *headroom) : *headroom;
      const size_t slash = path.find_last_of('/');
      if (path == "/" || slash == std::string::npos) break;
      path.resize(slash == 0 ? 1 : slash);
    }
  }
  return best;
}

/// What RLIMIT_AS still leaves of the address space; nullopt when unlimited.
std::optional<uint64_t> address_space_available() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  uint64_t used = 0;
  if (const std::optional<std::string> statm = read_small_file("/proc/self/statm")) {
    std::istringstream in(*statm);
    in >> used;
    used *= static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
  }
  return limit.rlim_cur > used ? limit.rlim_cur - used : 0;
}

}  // namespace

std::optional<uint64_t> parse_meminfo_available(std::string_view meminfo) {
  const std::string_view key = "MemAvailable:";
  const size_t at = meminfo.find(key);
  if (at == std::string_view::npos || (at > 0 && meminfo[at - 1] != '\n')) return std::nullopt;
  std::string_view rest = meminfo.substr(at + key.size());
  while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  uint64_t kib = 0;
  const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), kib);
  if (ec != std::errc() || end == rest.data()) return std::nullopt;
  if (std::string_view(end, static_cast<size_t>(rest.data() + rest.size() - end)).substr(0, 3) != " kB")
    return std::nullopt;
  return kib * 1024;
}

MemoryBudget available_memory() {
  MemoryBudget budget{std::numeric_limits<uint64_t>::max(), "no known limit"};
  auto consider = [&](std::optional<uint64_t> bytes, const char* source) {
    if (bytes && *bytes < budget.bytes) budget = {*bytes, source};
  };
  if (const std::optional<std::string> meminfo = read_small_file("/proc/meminfo"))
    consider(parse_meminfo_available(*meminfo), "MemAvailable in /proc/meminfo");
  if (budget.bytes == std::numeric_limits<uint64_t>::max()) {
    const long pages = ::sysconf(_SC_AVPHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) consider(static_cast<uint64_t>(pages) * static_cast<uint64_t>(page), "free memory");
  }
  consider(cgroup_available(), "the cgroup memory limit");
  consider(address_space_available(), "the address-space limit (ulimit -v)");
  if (const char* cap = std::getenv("LUEUR_MEMORY_LIMIT_MB"); cap && *cap) {
    const std::optional<uint64_t> megabytes = parse_u64(cap);
    if (!megabytes || *megabytes == 0 || *megabytes > (uint64_t{1} << 40))
      throw std::invalid_argument(std::string("LUEUR_MEMORY_LIMIT_MB: '") + cap + "' is not a number of megabytes");
    consider(*megabytes << 20, "LUEUR_MEMORY_LIMIT_MB");
  }
  return budget;
}

std::string format_bytes(uint64_t bytes) {
  static constexpr const char* kUnits[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = static_cast<double>(bytes);
  size_t unit = 0;
  while (value >= 1024.0 && unit + 1 < std::size(kUnits)) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, kUnits[unit]);
  return text;
}

void map_large_arrays_alone() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 4 << 20);  // setting it also turns off glibc's own raising of it
#endif
}

void release_free_memory() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

uint64_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    std::istringstream fields(line.substr(6));
    uint64_t kib = 0;
    if (fields >> kib) return kib * 1024;
  }
  return 0;
}

}  // namespace lueur
