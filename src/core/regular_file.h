// Reading a whole file that must be a regular one: FIFOs, devices and directories are refused (a FIFO would block,
// /dev/zero never ends), and so is a file larger than the caller allows. Depends on the standard library only.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

namespace lueur {

/// One line naming the file: "cannot open 'P': Is a directory", "cannot read 'P': ...".
struct FileReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Called with the file's size before it is read, and again with the bytes read whenever a file that grows while
/// it is read passes that size: it throws (an error of the caller's kind) where that is more than may be held.
using FileSizeCheck = std::function<void(uint64_t bytes)>;

/// Told the bytes read so far and the file's size as a large file is read.
using FileReadProgress = std::function<void(uint64_t bytes_read, uint64_t size)>;

/// The whole of the regular file `path`; FileReadError where it cannot be opened or read or is not a regular file.
std::string read_regular_file(const std::string& path, const FileSizeCheck& check_size,
                              const FileReadProgress& progress = {});

/// The same, refusing (FileReadError) a file of more than `max_bytes`.
std::string read_regular_file(const std::string& path, uint64_t max_bytes);

}  // namespace lueur
