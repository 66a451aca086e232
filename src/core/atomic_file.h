// Writes whole files so that a reader sees either the old file or the complete new one, never a half-written one.
// Depends on the standard library only.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace lueur {

/// An input or output problem, with a one-line message that names the file.
struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Writes `bytes` to a temporary file beside `path`, flushes it to disk and renames it over `path`.
/// On any failure the temporary file is removed, `path` is untouched, and IoError names the file.
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace lueur
