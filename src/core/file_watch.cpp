// Stamping files and noticing settled changes (see file_watch.h).
#include "core/file_watch.h"

#include <sys/stat.h>

namespace lueur {

FileStamp stamp_file(const std::string& path) {
  struct stat info {};
  FileStamp stamp;
  if (::stat(path.c_str(), &info) != 0) return stamp;
  stamp.exists = true;
  stamp.size = static_cast<uint64_t>(info.st_size);
  stamp.inode = static_cast<uint64_t>(info.st_ino);
  stamp.modified_ns = static_cast<int64_t>(info.st_mtim.tv_sec) * 1000000000 + info.st_mtim.tv_nsec;
  return stamp;
}

void FileWatch::watch(std::vector<WatchedFile> files) {
  files_ = std::move(files);
  pending_ = false;
  reported_ = false;
  pending_stamps_.clear();
  last_poll_ = -1e300;
}

std::vector<FileStamp> FileWatch::stamps_now() const {
  std::vector<FileStamp> stamps;
  stamps.reserve(files_.size());
  for (const WatchedFile& file : files_) stamps.push_back(stamp_file(file.path));
  return stamps;
}

bool FileWatch::changed(double now_seconds) {
  if (files_.empty() || reported_ || now_seconds - last_poll_ < poll_seconds_) return false;
  last_poll_ = now_seconds;
  std::vector<FileStamp> now = stamps_now();
  bool same_as_watched = true;
  for (size_t i = 0; i < files_.size(); ++i) same_as_watched = same_as_watched && now[i] == files_[i].stamp;
  if (same_as_watched) {  // changed and changed back (or touched by nothing): nothing to reload
    pending_ = false;
    return false;
  }
  if (!pending_ || now != pending_stamps_) {  // a new change, or one still being written
    pending_ = true;
    pending_stamps_ = std::move(now);
    pending_since_ = now_seconds;
    return false;
  }
  if (now_seconds - pending_since_ < settle_seconds_) return false;
  reported_ = true;
  return true;
}

}  // namespace lueur
