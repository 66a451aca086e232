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
///
/// The temporary file is unnamed (O_TMPFILE) where the filesystem allows, so a process killed while writing
/// leaves nothing behind; it gets a name only for the instant before the rename. Elsewhere it is the hidden
/// `.<name>.lueur-tmp-<pid>` beside `path`, which a kill can leave behind but never looks like output.
///
/// Test hook: with the environment variable LUEUR_TEST_PAUSE_MID_WRITE=SECONDS, the writer stops after half of
/// the bytes, prints "lueur: test hook: paused mid-write of 'PATH'" on stderr and sleeps that long before going
/// on, so that a test can kill the process in the middle of a write deterministically. With
/// LUEUR_TEST_NO_TMPFILE=1 it skips O_TMPFILE and takes the named fallback, as on a filesystem without it.
void write_file_atomically(const std::string& path, std::string_view bytes);

/// The name of the hidden temporary file used beside `path` where O_TMPFILE is not available.
std::string named_temp_path(const std::string& path, long pid);

}  // namespace lueur
