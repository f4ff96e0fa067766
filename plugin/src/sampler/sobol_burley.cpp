#include "sampler/sobol_burley.h"

namespace bxdf::render::sobol {

namespace {

// Joe and Kuo's primitive polynomials and initial direction numbers ("new-joe-kuo-6.21201",
// dimensions 2 to 4; dimension 1 is van der Corput): degree s, coefficients a, m_1..m_s.
struct Polynomial {
  int degree;
  uint32_t coefficients;
  uint32_t initial[3];
};
constexpr Polynomial kPolynomials[kDimensions - 1] = {
    {1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}};

// V_i = m_i / 2^i as 32-bit fractions, extended by Bratley and Fox's recurrence
// V_i = a_1 V_{i-1} ^ ... ^ a_{s-1} V_{i-s+1} ^ V_{i-s} ^ (V_{i-s} >> s).
constexpr std::array<std::array<uint32_t, 32>, kDimensions> make_directions() {
  std::array<std::array<uint32_t, 32>, kDimensions> table{};
  for (int i = 0; i < 32; ++i) table[0][static_cast<std::size_t>(i)] = 1u << (31 - i);
  for (int d = 1; d < kDimensions; ++d) {
    const Polynomial& p = kPolynomials[d - 1];
    std::array<uint32_t, 32>& v = table[static_cast<std::size_t>(d)];
    for (int i = 0; i < p.degree; ++i) v[static_cast<std::size_t>(i)] = p.initial[i] << (31 - i);
    for (int i = p.degree; i < 32; ++i) {
      const int s = p.degree;
      uint32_t x = v[static_cast<std::size_t>(i - s)] ^ (v[static_cast<std::size_t>(i - s)] >> s);
      for (int k = 1; k < s; ++k)
        if ((p.coefficients >> (s - 1 - k)) & 1u) x ^= v[static_cast<std::size_t>(i - k)];
      v[static_cast<std::size_t>(i)] = x;
    }
  }
  return table;
}

constexpr std::array<std::array<uint32_t, 32>, kDimensions> kDirections = make_directions();

constexpr std::array<ByteTables, kDimensions> make_byte_tables() {
  std::array<ByteTables, kDimensions> tables{};
  for (std::size_t d = 0; d < kDimensions; ++d)
    for (std::size_t byte = 0; byte < 4; ++byte)
      for (uint32_t value = 0; value < 256; ++value) {
        uint32_t x = 0;
        for (std::size_t bit = 0; bit < 8; ++bit)
          if ((value >> bit) & 1u) x ^= kDirections[d][8 * byte + bit];
        tables[d][byte][value] = x;
      }
  return tables;
}

constexpr std::array<ByteTables, kDimensions> kByteTables = make_byte_tables();

constexpr uint32_t reverse_constexpr(uint32_t x, int bits) {
  uint32_t r = 0;
  for (int i = 0; i < bits; ++i) r |= ((x >> i) & 1u) << (bits - 1 - i);
  return r;
}

// Byte j of reverse_bits(index) is byte 3 - j of index, its bits reversed.
constexpr std::array<ByteTables, kDimensions> make_reversed_byte_tables() {
  std::array<ByteTables, kDimensions> tables{};
  for (std::size_t d = 0; d < kDimensions; ++d)
    for (std::size_t byte = 0; byte < 4; ++byte)
      for (uint32_t value = 0; value < 256; ++value)
        tables[d][byte][value] =
            reverse_constexpr(kByteTables[d][3 - byte][reverse_constexpr(value, 8)], 32);
  return tables;
}

constexpr std::array<ByteTables, kDimensions> kReversedByteTables = make_reversed_byte_tables();

}  // namespace

const std::array<uint32_t, 32>& directions(int d) { return kDirections[static_cast<std::size_t>(d)]; }

const ByteTables& byte_tables(int d) { return kByteTables[static_cast<std::size_t>(d)]; }

const ByteTables& reversed_byte_tables(int d) {
  return kReversedByteTables[static_cast<std::size_t>(d)];
}

}  // namespace bxdf::render::sobol
