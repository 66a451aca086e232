// Text helpers of the OBJ loader: tokens, quoted tokens, strict numbers and message pieces (see obj_text.h).
// Depends on core and obj_loader.h only; never on tinyobjloader.
#include "scene/obj_text.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "scene/obj_loader.h"

namespace lueur::obj {

using std::string_view;

string_view trim(string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

TextScan scan_text(string_view text) {
  // Per-byte flags or-ed together, no early exit: a loop the compiler vectorises.
  unsigned char binary = 0;
  unsigned char carriage_return = 0;
  for (const char byte : text) {
    const auto c = static_cast<unsigned char>(byte);
    binary |= static_cast<unsigned char>(is_binary_byte(c));
    carriage_return |= static_cast<unsigned char>(c == '\r');
  }
  return {binary != 0, carriage_return != 0};
}

string_view next_token(string_view& rest) {
  size_t begin = 0;
  while (begin < rest.size() && is_blank(rest[begin])) ++begin;
  size_t end = begin;
  while (end < rest.size() && !is_blank(rest[end])) ++end;
  const string_view token = rest.substr(begin, end - begin);
  rest.remove_prefix(end);
  return token;
}

std::string printable(string_view token, size_t max_chars) {
  std::string out;
  for (size_t i = 0; i < token.size(); ++i) {
    if (out.size() >= max_chars) {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

void fail_at(const std::string& label, size_t line, const std::string& what) {
  throw SceneError(label + ":" + std::to_string(line) + ": " + what);
}

std::string too_large(const std::string& what, uint64_t needed, const MemoryBudget& budget) {
  return "scene too large: " + what + " about " + format_bytes(needed) + " of memory, more than the " +
         format_bytes(budget.bytes) + " available (" + budget.source + ")";
}

std::string counted(size_t n, const std::string& noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

NumberStatus parse_float(string_view token, float& out) {
  // tinyobjloader accepts a leading '+', std::from_chars does not; "+-1" stays an error for both.
  if (token.size() > 1 && token[0] == '+' && (std::isdigit(static_cast<unsigned char>(token[1])) || token[1] == '.'))
    token.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec == std::errc::result_out_of_range && end == token.data() + token.size()) return NumberStatus::not_finite;
  if (ec != std::errc() || end != token.data() + token.size()) return NumberStatus::not_a_number;
  out = static_cast<float>(value);
  return std::isfinite(out) ? NumberStatus::ok : NumberStatus::not_finite;
}

float lenient_float(string_view token) {
  const auto digit = [&](size_t i) { return i < token.size() && std::isdigit(static_cast<unsigned char>(token[i])); };
  size_t i = 0;
  const bool negative = i < token.size() && token[i] == '-';
  if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
  const size_t mantissa_begin = i;
  size_t mantissa_digits = 0;
  while (digit(i)) ++i, ++mantissa_digits;
  if (i < token.size() && token[i] == '.') {
    ++i;
    while (digit(i)) ++i, ++mantissa_digits;
  } else if (mantissa_digits == 0) {
    return 0.0f;  // neither a digit nor a '.': not a number
  }
  const size_t mantissa_end = i;
  long exponent = 0;
  if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
    ++i;
    const bool negative_exponent = i < token.size() && token[i] == '-';
    if (i < token.size() && (token[i] == '+' || token[i] == '-')) ++i;
    if (!digit(i)) return 0.0f;  // an exponent without digits spoils the whole number
    for (; digit(i); ++i) {
      if (exponent > 214748364) return 0.0f;  // beyond int: refused, like a malformed exponent
      exponent = 10 * exponent + (token[i] - '0');
    }
    if (negative_exponent) exponent = -exponent;
  }
  // "5." and ".5" read as such; a mantissa of no digits at all ("." or "-.") is zero.
  if (mantissa_digits == 0) return negative ? -0.0f : 0.0f;
  std::string number(token.substr(mantissa_begin, mantissa_end - mantissa_begin));
  number += 'e';
  number += std::to_string(exponent);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (ec == std::errc::result_out_of_range) {
    value = std::strtod(number.c_str(), nullptr);  // too large: infinite; too small: zero or subnormal
  } else if (ec != std::errc() || end != number.data() + number.size()) {
    return 0.0f;
  }
  return static_cast<float>(negative ? -value : value);
}

NumberStatus parse_integer(string_view token, long long& out) {
  if (token.size() > 1 && token[0] == '+' && std::isdigit(static_cast<unsigned char>(token[1]))) token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  if (end != token.data() + token.size() || token.empty()) return NumberStatus::not_a_number;
  if (ec == std::errc::result_out_of_range) return NumberStatus::not_finite;
  return ec == std::errc() ? NumberStatus::ok : NumberStatus::not_a_number;
}

}  // namespace lueur::obj
