// Equal normals sharing one index (the smooth-normal pass, smooth_normals.cpp): an open-addressing table whose slots
// hold the key and its index together, so that a look-up costs one cache line, not two.
// Depends on core only.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/huge_pages.h"
#include "core/math.h"

namespace lueur {

/// Equal normals (bit for bit, -0 folded into +0) share one index, given in the order they were first seen.
class NormalInterner {
 public:
  static constexpr uint32_t kNotFound = 0xffffffffu;

  /// Sized for about `expected` distinct normals (it grows past them).
  explicit NormalInterner(size_t expected = 0) {
    normals.reserve(expected);
    resize(expected);
  }

  uint32_t intern(const Vec3& n) {
    if (2 * (normals.size() + 1) > slots_.size()) resize(2 * normals.size() + 2);
    const Key key = key_of(n);
    Slot& slot = slots_[slot_of(key)];
    if (slot.index == kNotFound) {
      slot = {key, static_cast<uint32_t>(normals.size())};
      normals.push_back(n);
    }
    return slot.index;
  }

  /// Starts fetching the slot where `n` is looked up, so that a look-up a little later finds it at hand.
  void prefetch(const Vec3& n) const { __builtin_prefetch(&slots_[hash(key_of(n)) & mask_]); }

  /// The index of a normal equal to `n`, or kNotFound.
  uint32_t find(const Vec3& n) const {
    const Key key = key_of(n);
    return slots_[slot_of(key)].index;
  }

  std::vector<Vec3> normals;

 private:
  struct Key {
    uint32_t bits[3];
    bool operator==(const Key& other) const {
      return bits[0] == other.bits[0] && bits[1] == other.bits[1] && bits[2] == other.bits[2];
    }
  };
  struct Slot {
    Key key;
    uint32_t index;
  };

  static Key key_of(const Vec3& v) {
    Key key{};
    for (int i = 0; i < 3; ++i) {
      const float value = v[i] + 0.0f;
      std::memcpy(&key.bits[i], &value, sizeof value);
    }
    return key;
  }
  static size_t hash(const Key& key) {
    // Every bit of the three floats moves every bit of the slot (a 64-bit finaliser): smooth normals differ in few
    // bits, and linear probing punishes clusters.
    uint64_t h = (uint64_t{key.bits[0]} << 32 | key.bits[1]) ^ (uint64_t{key.bits[2]} * 0x9e3779b97f4a7c15ull);
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return static_cast<size_t>(h);
  }
  /// The slot holding `key`, or the empty slot where it would go.
  size_t slot_of(const Key& key) const {
    for (size_t at = hash(key) & mask_;; at = (at + 1) & mask_)
      if (slots_[at].index == kNotFound || slots_[at].key == key) return at;
  }
  /// At least twice `count` slots (a power of two), the present normals placed again.
  void resize(size_t count) {
    size_t size = 1024;
    while (size < 2 * count) size *= 2;
    if (size <= slots_.size()) return;
    slots_.assign(size, Slot{{}, kNotFound});
    mask_ = size - 1;
    for (uint32_t index = 0; index < normals.size(); ++index) {
      const Key key = key_of(normals[index]);
      slots_[slot_of(key)] = {key, index};
    }
  }

  HugePageVector<Slot> slots_;  // huge pages: every look-up lands somewhere new
  size_t mask_ = 0;
};

}  // namespace lueur
