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

/// The 32 bits of x in reverse order. At run time four lookups in a 256-byte table, which the sampler's five
/// reversals per sample find in cache: shorter than the five dependent shift-and-mask steps.
constexpr uint32_t reverse_bits(uint32_t x) {
  if (!std::is_constant_evaluated()) {
    return (static_cast<uint32_t>(kReversedBytes[x & 0xffu]) << 24) |
           (static_cast<uint32_t>(kReversedBytes[(x >> 8) & 0xffu]) << 16) |
           (static_cast<uint32_t>(kReversedBytes[(x >> 16) & 0xffu]) << 8) | kReversedBytes[x >> 24];
  }
  x = (x << 16) | (x >> 16);
  x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
  x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
  x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
  x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
  return x;
}

/// Sobol's first dimension for `index`, as a 32-bit fraction: the van der Corput sequence (the bits reversed).
inline uint32_t sobol_dimension_0(uint32_t index) { return reverse_bits(index); }

/// Xor tables of direction numbers, one per byte of the index: `tables[b][value]` is the xor of the direction
/// numbers of the set bits of `value << 8b`.
using SobolByteTables = std::array<std::array<uint32_t, 256>, 4>;

constexpr SobolByteTables make_sobol_byte_tables(const std::array<uint32_t, 32>& directions) {
  SobolByteTables tables{};
  for (size_t byte = 0; byte < 4; ++byte)
    for (uint32_t value = 0; value < 256; ++value)
      for (size_t bit = 0; bit < 8; ++bit)
        if (value & (1u << bit)) tables[byte][value] ^= directions[8 * byte + bit];
  return tables;
}

/// Sobol's second dimension (primitive polynomial x + 1): the direction numbers are the rows of Pascal's triangle
/// mod 2, v_0 = 2^31 and v_j = v_(j-1) xor (v_(j-1) >> 1).
inline constexpr std::array<uint32_t, 32> kSobolDimension1Directions = [] {
  std::array<uint32_t, 32> v{};
  v[0] = 0x80000000u;
  for (size_t j = 1; j < v.size(); ++j) v[j] = v[j - 1] ^ (v[j - 1] >> 1);
  return v;
}();
inline constexpr SobolByteTables kSobolDimension1Tables = make_sobol_byte_tables(kSobolDimension1Directions);

/// Xors the table entries of the four bytes of `index`: four lookups, where a loop over the bits would pay a
/// mispredicted branch for every other bit of a scrambled index.
inline uint32_t xor_by_bytes(const SobolByteTables& tables, uint32_t index) {
  return tables[0][index & 0xffu] ^ tables[1][(index >> 8) & 0xffu] ^ tables[2][(index >> 16) & 0xffu] ^
         tables[3][index >> 24];
}

/// Sobol's second dimension for `index`, as a 32-bit fraction: the xor of the direction numbers of its set bits.
inline uint32_t sobol_dimension_1(uint32_t index) { return xor_by_bytes(kSobolDimension1Tables, index); }

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
