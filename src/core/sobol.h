// Owen-scrambled Sobol points in two dimensions, with hash-based nested uniform scrambling (Burley 2020,
// "Practical Hash-based Owen Scrambling"). Sobol's first two dimensions form a (0,2)-sequence: every aligned block
// of 2^k points has exactly one point in each elementary interval of area 2^-k, and a nested uniform scramble of
// the points (or of the index) keeps that. Depends on the standard library only.
#pragma once

#include <array>
#include <cstdint>
#include <type_traits>

namespace lueur {

/// Each byte value with its bits reversed.
inline constexpr std::array<uint8_t, 256> kReversedBytes = [] {
  std::array<uint8_t, 256> table{};
  for (uint32_t value = 0; value < 256; ++value)
    for (uint32_t bit = 0; bit < 8; ++bit)
      if (value & (1u << bit)) table[value] |= static_cast<uint8_t>(0x80u >> bit);
  return table;
}();

/// The 32 bits of x in reverse order by five swap steps: branch-free arithmetic that a loop over several samples
/// runs in SIMD lanes.
constexpr uint32_t reverse_bits_by_shifts(uint32_t x) {
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  return x;
}

/// The 32 bits of x in reverse order. At run time four lookups in a 256-byte table, which the sampler's five
/// reversals per sample find in cache: shorter than the five dependent steps one sample at a time.
constexpr uint32_t reverse_bits(uint32_t x) {
  if (std::is_constant_evaluated()) return reverse_bits_by_shifts(x);
  return (static_cast<uint32_t>(kReversedBytes[x & 0xffu]) << 24) |
         (static_cast<uint32_t>(kReversedBytes[(x >> 8) & 0xffu]) << 16) |
         (static_cast<uint32_t>(kReversedBytes[(x >> 16) & 0xffu]) << 8) | kReversedBytes[x >> 24];
}

/// Sobol's first dimension for `index`, as a 32-bit fraction: the van der Corput sequence (the bits reversed).
inline uint32_t sobol_dimension_0(uint32_t index) { return reverse_bits(index); }

/// Sobol's second dimension (primitive polynomial x + 1): the direction numbers are the rows of Pascal's triangle
/// mod 2, v_0 = 2^31 and v_j = v_(j-1) xor (v_(j-1) >> 1). The reference definition; the sampler uses
/// `sobol_dimension_1_reversed`.
inline constexpr std::array<uint32_t, 32> kSobolDimension1Directions = [] {
  std::array<uint32_t, 32> v{};
  v[0] = 0x80000000u;
  for (size_t j = 1; j < v.size(); ++j) v[j] = v[j - 1] ^ (v[j - 1] >> 1);
  return v;
}();

/// Sobol's second dimension with its bits reversed (bit k is the fraction's bit 31 - k), without tables. By
/// Lucas's theorem, bit 31 - k of v_j is C(j, k) mod 2 = [the bits of k are among those of j], so bit k of the
/// result is the parity of the index's set bits j whose positions contain k: a sum over supersets, which five
/// shift-and-xor steps (one per bit of the 5-bit position) compute for all 32 positions at once.
constexpr uint32_t sobol_dimension_1_reversed(uint32_t index) {
  uint32_t g = index;
  g ^= (g >> 1) & 0x55555555u;
  g ^= (g >> 2) & 0x33333333u;
  g ^= (g >> 4) & 0x0f0f0f0fu;
  g ^= (g >> 8) & 0x00ff00ffu;
  g ^= (g >> 16) & 0x0000ffffu;
  return g;
}

/// Sobol's second dimension for `index`, as a 32-bit fraction.
inline uint32_t sobol_dimension_1(uint32_t index) { return reverse_bits(sobol_dimension_1_reversed(index)); }

/// The hash at the heart of a nested uniform scramble, on reversed bits: each bit is flipped by a function of the
/// bits below it, which additions and multiplications by even constants respect (Laine and Karras 2011, with
/// Burley's constants).
inline uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

/// A nested uniform (Owen) scramble of a 32-bit fraction, seeded: each bit is flipped by a hash of the bits above
/// it.
inline uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

/// A 32-bit fraction as a float in [0, 1): its top 24 bits, so that it never rounds up to 1.
inline float fraction_to_float(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

}  // namespace lueur
