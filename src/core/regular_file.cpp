// Whole regular files read through one descriptor, with the size checked before and while reading.
#include "core/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "core/memory_budget.h"

namespace lueur {
namespace {

/// "cannot open 'path': reason" for the errno just set: read before the message's strings are built, since an
/// allocation may change errno.
FileReadError system_error(const char* what, const std::string& path) {
  const int why = errno;
  return FileReadError(std::string(what) + " '" + path + "': " + std::strerror(why));
}

/// Closes the descriptor on every way out.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_regular_file(const std::string& path, const FileSizeCheck& check_size,
                              const FileReadProgress& progress) {
  Descriptor file;
  // O_NONBLOCK: opening a FIFO with no writer must not wait for one (it is refused just below).
  file.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (file.fd < 0) throw system_error("cannot open", path);
  struct stat info {};
  if (::fstat(file.fd, &info) != 0) throw system_error("cannot open", path);
  if (!S_ISREG(info.st_mode))
    throw FileReadError("cannot open '" + path + "': " +
                        (S_ISDIR(info.st_mode) ? std::string(std::strerror(EISDIR)) : std::string("not a regular file")));
  const uint64_t size = static_cast<uint64_t>(info.st_size);
  check_size(size);
  // Read straight into the string, in pieces large enough to go at the disk's speed and small enough to report.
  constexpr size_t kPiece = size_t{8} << 20;
  std::string text(static_cast<size_t>(size), '\0');
  size_t filled = 0;
  char spill[1 << 16];  // past the size stat gave: the end of the file, or a file that grows while it is read
  while (true) {
    const bool full = filled == text.size();
    const ssize_t n = full ? ::read(file.fd, spill, sizeof spill)
                           : ::read(file.fd, text.data() + filled, std::min(text.size() - filled, kPiece));
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw system_error("cannot read", path);
    }
    if (full) text.append(spill, static_cast<size_t>(n));
    filled += static_cast<size_t>(n);
    if (filled > size) check_size(filled);
    if (progress) progress(filled, size);
  }
  text.resize(filled);
  return text;
}

std::string read_regular_file(const std::string& path, uint64_t max_bytes) {
  return read_regular_file(path, [&](uint64_t bytes) {
    if (bytes > max_bytes)
      throw FileReadError("'" + path + "' is " + format_bytes(bytes) + ", more than " + format_bytes(max_bytes) +
                          " such a file can be");
  });
}

}  // namespace lueur
