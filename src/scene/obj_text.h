// Text helpers shared by the steps of the OBJ loader (validator, MTL scan, conversion, file reading): blank-separated
// tokens, line splitting that numbers lines as tinyobjloader does, strict number parsing, and the pieces of the
// loader's one-line messages. Internal to src/scene; depends on core and obj_loader.h (SceneError) only, never on
// tinyobjloader.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "core/memory_budget.h"

namespace lueur::obj {

/// The blanks that separate tokens in OBJ and MTL statements.
inline bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// Bytes that never appear in a text OBJ/MTL: NUL, the C0 controls other than tab/CR/LF, and DEL.
/// Written with `&` and `|`, not `&&` and `||`, so that loops over many bytes vectorise (scan_text).
inline bool is_binary_byte(unsigned char c) {
  return ((c < 0x20) & (c != '\t') & (c != '\n') & (c != '\r')) | (c == 0x7f);
}

/// `s` without leading and trailing blanks.
std::string_view trim(std::string_view s);

/// Splits off the next blank-separated token; `rest` keeps what follows it.
std::string_view next_token(std::string_view& rest);

/// A token quoted for a one-line message: control and non-ASCII bytes escaped, long tokens cut.
std::string printable(std::string_view token, size_t max_chars = 32);

/// What one pass over a text found: whether it holds a byte no text has (is_binary_byte) and any '\r'.
struct TextScan {
  bool binary = false;
  bool carriage_return = false;
};

/// Scans `text` in one branch-free pass (the compiler turns it into vector code), so that text without binary bytes
/// or carriage returns, nearly all of it, is neither checked byte by byte nor cut into lines byte by byte.
TextScan scan_text(std::string_view text);

/// Calls `visit(line_number, line)` for every line, splitting at "\n", "\r\n" and a lone "\r" exactly as
/// tinyobjloader's safeGetline does, so that our line numbers are its line numbers. `carriage_return` false (from
/// scan_text) promises no '\r' in `text`: lines are then found with memchr.
template <typename Visit>
void for_each_line(std::string_view text, Visit&& visit, bool carriage_return = true) {
  size_t line_number = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = pos;
    if (!carriage_return) {
      const void* newline = std::memchr(text.data() + pos, '\n', text.size() - pos);
      end = newline ? static_cast<size_t>(static_cast<const char*>(newline) - text.data()) : text.size();
    } else {
      while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
    }
    ++line_number;
    visit(line_number, text.substr(pos, end - pos));
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ++end;
    pos = end + 1;
  }
}

/// Throws SceneError "label:line: what".
[[noreturn]] void fail_at(const std::string& label, size_t line, const std::string& what);

/// "scene too large: <what> about 3.1 GiB of memory, more than the 2.0 GiB available (MemAvailable in /proc/meminfo)".
std::string too_large(const std::string& what, uint64_t needed, const MemoryBudget& budget);

/// "1 triangle", "2 triangles".
std::string counted(size_t n, const std::string& noun);

enum class NumberStatus { ok, not_a_number, not_finite };

/// Parses a whole token as a float: rejects trailing junk ("1.5abc"), NaN, infinities and values beyond float.
NumberStatus parse_float(std::string_view token, float& out);

/// Reads a normal's or texture coordinate's value as OBJ readers do: the longest leading number
/// ([+-] digits [. digits] [e [+-] digits], or a leading '.'), rounded correctly, and 0 where the token does not
/// start with one or its exponent is malformed ("1.5abc" is 1.5, "abc" and "1e" are 0, "1e999" is infinite).
float lenient_float(std::string_view token);

/// Parses a whole token as an integer; not_finite stands for "beyond long long".
NumberStatus parse_integer(std::string_view token, long long& out);

}  // namespace lueur::obj
