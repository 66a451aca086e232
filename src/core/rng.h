// Counter-based random numbers: every stream is a pure function of (seed, pixel, frame, purpose), so an image
// never depends on which thread rendered which tile. Depends on the standard library only.
#pragma once

#include <cstdint>

namespace lueur {

/// A strong 64-bit mixer (the finaliser of SplitMix64): nearby inputs give unrelated outputs.
inline uint64_t mix64(uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  x ^= x >> 31;
  return x;
}

inline uint64_t hash_combine(uint64_t seed, uint64_t value) { return mix64(seed ^ (value + 0x9e3779b97f4a7c15ull)); }

/// PCG32 (O'Neill): small state, good statistics, and a stream selector so that streams never overlap.
class Pcg32 {
 public:
  Pcg32(uint64_t state_seed, uint64_t stream) : inc_((stream << 1u) | 1u) {
    next_u32();
    state_ += state_seed;
    next_u32();
  }

  uint32_t next_u32() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  /// Uniform in [0, 1): 24 random bits, so the result is exactly representable and never rounds up to 1.
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_ = 0;
  uint64_t inc_;
};

/// What a stream is used for: separate streams keep passes independent of each other's sample counts.
enum class RngPurpose : uint64_t {
  kCamera = 1,
  kDirect = 2,
  kIndirect = 3,
  kOcclusion = 4,
  kRecompute = 5,
  kEmission = 6,     ///< the camera rays that only see Le (RenderSettings::le_rays, when more than one)
  kCacheFeed = 7,    ///< where a primary hit's L1 goes into the L1 store (the jitter within a cell)
  kCacheLookup = 8,  ///< where L2's bounce hits look up (and feed) the L1 store
  kPath = 9,         ///< ln's paths: the second and later bounces
};

/// The stream of one pixel in one frame for one purpose.
inline Pcg32 make_pixel_rng(uint64_t seed, uint64_t pixel, uint64_t frame, RngPurpose purpose) {
  const uint64_t key = hash_combine(hash_combine(hash_combine(seed, pixel), frame), static_cast<uint64_t>(purpose));
  return Pcg32(key, mix64(key ^ 0x5851f42d4c957f2dull));
}

}  // namespace lueur
