// Plain little-endian byte streams for Lueur's own binary files (the resume state): append values to a string, read
// them back with every read checked against the end. Depends on the standard library only.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace lueur {

/// A byte stream that ended early or holds an impossible value; the message says what was being read.
struct ByteStreamError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ByteWriter {
  std::string bytes;
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  template <typename T>
  void put_array(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(values.size());
    if (!values.empty()) bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  void put_string(std::string_view text) {
    put<uint64_t>(text.size());
    bytes.append(text);
  }
};

struct ByteReader {
  std::string_view bytes;
  size_t at = 0;
  template <typename T>
  T get(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return value;
  }
  /// An array of at most `max_count` values (so that a corrupt count cannot ask for all of memory).
  template <typename T>
  std::vector<T> get_array(uint64_t max_count, const char* what) {
    const uint64_t count = get<uint64_t>(what);
    if (count > max_count) throw ByteStreamError(std::string("impossible size of ") + what);
    need(count * sizeof(T), what);
    std::vector<T> values(count);
    if (count > 0) std::memcpy(values.data(), bytes.data() + at, count * sizeof(T));  // empty: data() may be null
    at += count * sizeof(T);
    return values;
  }
  std::string get_string(const char* what) {
    const uint64_t size = get<uint64_t>(what);
    need(size, what);
    std::string text(bytes.substr(at, size));
    at += size;
    return text;
  }
  void need(uint64_t size, const char* what) const {
    if (size > bytes.size() - at) throw ByteStreamError(std::string("it ends in the middle of ") + what);
  }
};

/// FNV-1a, 64 bits: a check that a file was not cut short or altered by accident.
inline uint64_t fnv1a64(std::string_view bytes) {
  uint64_t hash = 0xcbf29ce484222325ull;
  for (const char c : bytes) hash = (hash ^ static_cast<uint8_t>(c)) * 0x100000001b3ull;
  return hash;
}

}  // namespace lueur
