// Reloading a scene saved again: file stamps tell versions of a file apart, the watch reports a change only once it
// has settled (never a file half-written, never the same change twice), and the loader names every file a scene
// was read from or looked for, stamped as it was read.
#include <fcntl.h>
#include <sys/stat.h>

#include <cstdio>
#include <string>

#include "core/file_watch.h"
#include "obj_test_support.h"
#include "test_support.h"

namespace lueur {
namespace {

/// Sets `path`'s modification time to `seconds` since the epoch, so that two versions written within one clock
/// tick still differ (and one version can be made to look like another).
void set_modified(const std::string& path, time_t seconds) {
  const timespec times[2] = {{seconds, 0}, {seconds, 0}};
  ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), times, 0), 0) << path;
}

TEST(FileStamp, TellsMissingFilesSizesTimesAndReplacedFilesApart) {
  const std::string dir = test::make_temp_dir("file-stamp");
  const std::string path = dir + "/scene.obj";
  EXPECT_FALSE(stamp_file(path).exists);

  test::write_text(dir, "scene.obj", "v 0 0 0\n");
  set_modified(path, 1000000);
  const FileStamp first = stamp_file(path);
  EXPECT_TRUE(first.exists);
  EXPECT_EQ(first.size, 8u);
  EXPECT_EQ(first.modified_ns, int64_t{1000000} * 1000000000);
  EXPECT_EQ(stamp_file(path), first) << "nothing changed";

  test::write_text(dir, "scene.obj", "v 1 0 0\n");  // same size, written in place
  set_modified(path, 1000001);
  EXPECT_NE(stamp_file(path), first) << "a later modification time";

  // An editor saving by renaming a new file into place, same size and time: a new inode.
  set_modified(path, 1000000);
  const FileStamp before_rename = stamp_file(path);
  test::write_text(dir, "scene.obj.new", "v 1 0 0\n");
  set_modified(dir + "/scene.obj.new", 1000000);
  ASSERT_EQ(std::rename((dir + "/scene.obj.new").c_str(), path.c_str()), 0);
  const FileStamp renamed = stamp_file(path);
  EXPECT_EQ(renamed.size, before_rename.size);
  EXPECT_EQ(renamed.modified_ns, before_rename.modified_ns);
  EXPECT_NE(renamed, before_rename);
}

class Watch : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("file-watch");
    path_ = test::write_text(dir_, "scene.obj", "v 0 0 0\n");
    set_modified(path_, 1000000);
    watch_.watch({{path_, stamp_file(path_)}});
  }

  void save(const std::string& text, time_t seconds) {
    test::write_text(dir_, "scene.obj", text);
    set_modified(path_, seconds);
  }

  std::string dir_, path_;
  FileWatch watch_{0.25, 0.5};  // polls at most every 0.25 s; a change must hold for 0.5 s
};

TEST_F(Watch, ReportsASavedFileOnceItHasSettledAndOnlyOnce) {
  EXPECT_FALSE(watch_.changed(0.0));
  EXPECT_FALSE(watch_.changed(1.0));
  save("v 0 0 0\nv 1 0 0\n", 1000001);
  EXPECT_FALSE(watch_.changed(1.1)) << "polled 0.1 s after the last poll: not yet looked at";
  EXPECT_FALSE(watch_.changed(1.3)) << "first seen: it may still be being written";
  EXPECT_FALSE(watch_.changed(1.6)) << "the same for 0.3 s only";
  EXPECT_TRUE(watch_.changed(1.9)) << "the same for 0.6 s: settled";
  EXPECT_FALSE(watch_.changed(2.5)) << "reported once";
  EXPECT_FALSE(watch_.changed(10.0));

  // The caller reloads and watches the files as read: the next save is a new change.
  watch_.watch({{path_, stamp_file(path_)}});
  EXPECT_FALSE(watch_.changed(11.0));
  save("v 2 0 0\n", 1000002);
  EXPECT_FALSE(watch_.changed(11.3));
  EXPECT_TRUE(watch_.changed(11.9));
}

TEST_F(Watch, WaitsWhileAFileKeepsChanging) {
  save("v 0 0 0\nv 1", 1000001);  // an exporter halfway through the file
  EXPECT_FALSE(watch_.changed(1.0));
  save("v 0 0 0\nv 1 0 0\nv 2", 1000002);
  EXPECT_FALSE(watch_.changed(1.4)) << "changed again since the last poll: still being written";
  save("v 0 0 0\nv 1 0 0\nv 2 0 0\n", 1000003);
  EXPECT_FALSE(watch_.changed(1.8));
  EXPECT_FALSE(watch_.changed(2.1)) << "unchanged for 0.3 s only";
  EXPECT_TRUE(watch_.changed(2.4));
}

TEST_F(Watch, IgnoresAFileChangedBackToTheVersionWatched) {
  save("v 9 9 9\n", 1000001);
  EXPECT_FALSE(watch_.changed(1.0));
  save("v 0 0 0\n", 1000000);  // the version watched again: same bytes, size and time, same inode
  EXPECT_FALSE(watch_.changed(1.3));
  EXPECT_FALSE(watch_.changed(2.0));
  EXPECT_FALSE(watch_.changed(5.0));
}

TEST_F(Watch, ReportsAMissingFileThatAppearsAndAWatchedFileThatGoes) {
  const std::string mtl = dir_ + "/scene.mtl";
  watch_.watch({{path_, stamp_file(path_)}, {mtl, stamp_file(mtl)}});
  EXPECT_FALSE(watch_.changed(0.0));
  test::write_text(dir_, "scene.mtl", "newmtl red\nKd 1 0 0\n");
  EXPECT_FALSE(watch_.changed(1.0));
  EXPECT_TRUE(watch_.changed(2.0)) << "the missing MTL file appeared";

  watch_.watch({{path_, stamp_file(path_)}, {mtl, stamp_file(mtl)}});
  ASSERT_EQ(std::remove(mtl.c_str()), 0);
  EXPECT_FALSE(watch_.changed(3.0));
  EXPECT_TRUE(watch_.changed(4.0)) << "the MTL file was removed";
}

TEST(FileWatchEmpty, WatchingNothingNeverReports) {
  FileWatch watch;
  EXPECT_FALSE(watch.changed(0.0));
  EXPECT_FALSE(watch.changed(100.0));
  watch.watch({});
  EXPECT_FALSE(watch.changed(200.0));
}

TEST(SceneFiles, TheLoaderNamesEveryFileItReadOrLookedForStampedAsRead) {
  const std::string dir = test::make_temp_dir("scene-files");
  test::write_text(dir, "room.mtl",
                   "newmtl wall\nKd 0.5 0.5 0.5\nmap_Kd textures\\wall.png\nnewmtl floor\nKd 0.5 0.5 0.5\n"
                   "map_Kd absent.png\nnewmtl light\nKe 1 1 1\n");
  ASSERT_EQ(::mkdir((dir + "/textures").c_str(), 0755), 0);
  test::write_text(dir, "textures/wall.png", "not really a PNG");  // found, then refused as an image: still watched
  const std::string obj = test::write_text(dir, "room.obj",
                                           "mtllib room.mtl missing.mtl\n" + test::kTriangle +
                                               "usemtl wall\nf 1 2 3\nusemtl floor\nf 1 3 2\nusemtl light\nf 2 1 3\n");
  const FileStamp obj_stamp = stamp_file(obj);
  const LoadedScene loaded = load_obj(obj);
  const std::vector<WatchedFile> expected = {
      {obj, obj_stamp},
      {dir + "/room.mtl", stamp_file(dir + "/room.mtl")},
      {dir + "/missing.mtl", FileStamp{}},
      {dir + "/textures/wall.png", stamp_file(dir + "/textures/wall.png")},
      {dir + "/absent.png", FileStamp{}},
  };
  EXPECT_EQ(loaded.files, expected);
  EXPECT_TRUE(test::has_warning(loaded, "missing.mtl"));
  EXPECT_TRUE(test::has_warning(loaded, "absent.png"));

  // A scene given as text reads no file.
  EXPECT_TRUE(load_obj_from_text(test::kTriangle + "f 1 2 3\n", "", "text.obj").files.empty());
}

}  // namespace
}  // namespace lueur
