// Temporary file + fsync + rename: the only way Lueur writes output.
#include "core/atomic_file.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <thread>
#include <unistd.h>

namespace lueur {
namespace {

std::string directory_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

/// Seconds the LUEUR_TEST_PAUSE_MID_WRITE hook asks for; 0 when unset or malformed.
double test_pause_seconds() {
  const char* text = std::getenv("LUEUR_TEST_PAUSE_MID_WRITE");
  if (!text || !*text) return 0.0;
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  return (*end == '\0' && seconds > 0.0) ? seconds : 0.0;
}

/// The LUEUR_TEST_NO_TMPFILE hook: take the named fallback, as a filesystem without O_TMPFILE makes the writer do.
bool unnamed_temp_disabled() {
  const char* text = std::getenv("LUEUR_TEST_NO_TMPFILE");
  return text != nullptr && std::strcmp(text, "1") == 0;
}

/// Writes every byte and flushes it to disk (pausing halfway for the test hook). Returns 0 or an errno value.
int write_and_sync(int fd, std::string_view bytes, const std::string& path) {
  const double pause = test_pause_seconds();
  size_t written = 0;
  while (written < bytes.size()) {
    size_t limit = bytes.size();
    if (pause > 0.0 && written < bytes.size() / 2) limit = bytes.size() / 2;
    const ssize_t n = ::write(fd, bytes.data() + written, limit - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    written += static_cast<size_t>(n);
    if (pause > 0.0 && written == bytes.size() / 2) {
      std::fprintf(stderr, "lueur: test hook: paused mid-write of '%s'\n", path.c_str());
      std::fflush(stderr);
      std::this_thread::sleep_for(std::chrono::duration<double>(pause));
    }
  }
  return ::fsync(fd) == 0 ? 0 : errno;
}

/// Links the unnamed file `fd` as `temp` (replacing a stale file of that name). Returns 0 or an errno value.
int link_unnamed(int fd, const std::string& temp) {
  ::unlink(temp.c_str());
  const std::string proc = "/proc/self/fd/" + std::to_string(fd);
  return ::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, temp.c_str(), AT_SYMLINK_FOLLOW) == 0 ? 0 : errno;
}

/// Makes the rename itself durable. Best effort: the new file is already in place when this runs.
void sync_directory(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string named_temp_path(const std::string& path, long pid) {
  const size_t slash = path.find_last_of('/');
  std::string temp = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
  temp += '.';
  temp += path.substr(slash == std::string::npos ? 0 : slash + 1);
  temp += ".lueur-tmp-";
  temp += std::to_string(pid);
  return temp;
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  if (path.empty()) throw IoError("cannot write output: empty file name");
  auto failure = [&](int error) {
    std::string message = "cannot write '";
    message += path;
    message += "': ";
    message += std::strerror(error);
    return IoError(message);
  };
  const std::string temp = named_temp_path(path, static_cast<long>(::getpid()));

  // First choice: an unnamed file, named only for the instant between linkat and rename.
  int fd = unnamed_temp_disabled() ? -1 : ::open(directory_of(path).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
  if (fd >= 0) {
    const int write_error = write_and_sync(fd, bytes, path);
    const int link_error = write_error == 0 ? link_unnamed(fd, temp) : 0;
    ::close(fd);
    if (write_error != 0) throw failure(write_error);
    if (link_error == 0) {
      if (::rename(temp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(temp.c_str());
        throw failure(error);
      }
      sync_directory(directory_of(path));
      return;
    }
    // The link goes through /proc, which a sandbox may hide: then write again, to a named file.
  }

  // Fallback (no O_TMPFILE on this filesystem, or no /proc): a hidden named temporary file.
  fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) throw failure(errno);
  int error = write_and_sync(fd, bytes, path);
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error == 0 && ::rename(temp.c_str(), path.c_str()) != 0) error = errno;
  if (error != 0) {
    ::unlink(temp.c_str());
    throw failure(error);
  }
  sync_directory(directory_of(path));
}

}  // namespace lueur
