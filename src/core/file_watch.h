// Noticing that files changed on disk, so that the window can reload a scene whose OBJ, MTL or texture files were
// saved again (by an editor, or an exporter writing the scene anew). Depends on the standard library and POSIX only.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lueur {

/// What tells one version of a file from the next: whether it exists, its size, its inode (an editor that saves by
/// renaming a new file into place) and its modification time in nanoseconds.
struct FileStamp {
  bool exists = false;
  uint64_t size = 0, inode = 0;
  int64_t modified_ns = 0;
  bool operator==(const FileStamp&) const = default;
};

/// The stamp of `path` now; a path that cannot be examined (missing, no permission) has exists = false.
FileStamp stamp_file(const std::string& path);

/// A file a scene was read from (or looked for: a missing MTL or texture counts once it appears), with its stamp
/// taken just before it was read.
struct WatchedFile {
  std::string path;
  FileStamp stamp;
  bool operator==(const WatchedFile&) const = default;
};

/// Says when watched files have changed, once the change has settled: the files are stamped at most every
/// `poll_seconds`, and a change is reported only when two such polls at least `settle_seconds` apart found the same
/// new stamps, so that a file an exporter is still writing is not read half-written. Time comes from the caller.
class FileWatch {
 public:
  explicit FileWatch(double poll_seconds = 0.25, double settle_seconds = 0.25)
      : poll_seconds_(poll_seconds), settle_seconds_(settle_seconds) {}

  /// Watches these files from the stamps they carry (nothing: watches nothing).
  void watch(std::vector<WatchedFile> files);
  const std::vector<WatchedFile>& files() const { return files_; }

  /// True once when the files differ from the watched stamps and have settled; the caller then reloads and
  /// watches the new load's files. Reports the same change again only after watch().
  bool changed(double now_seconds);

 private:
  std::vector<FileStamp> stamps_now() const;

  double poll_seconds_, settle_seconds_;
  std::vector<WatchedFile> files_;
  double last_poll_ = -1e300;
  bool pending_ = false, reported_ = false;  ///< a change seen and not yet settled; a change reported
  std::vector<FileStamp> pending_stamps_;
  double pending_since_ = 0.0;
};

}  // namespace lueur
