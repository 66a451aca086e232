// The OBJ read on every core: a file cut into many chunks (of a few bytes to a few kilobytes, parsed on several
// threads) gives the same scene as a one-chunk read, on every scene at hand, and refuses a bad file with the same
// one-line message naming the same line, wherever in the chunks the bad line falls.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/default_scene.h"
#include "scene/obj_loader.h"
#include "scene/obj_writer.h"
#include "test_support.h"

namespace lueur {
namespace {

/// One way to read: chunk size and threads (chunk_bytes larger than any test text: one chunk).
struct Schedule {
  size_t chunk_bytes;
  unsigned threads;
};
constexpr Schedule kOneChunk{size_t{1} << 40, 1};
const std::vector<Schedule> kManyChunks = {{1, 3}, {7, 2}, {64, 3}, {1000, 1}, {4096, 4}};

LoadOptions options_for(const Schedule& schedule) {
  LoadOptions options;
  options.chunk_bytes = schedule.chunk_bytes;
  options.threads = schedule.threads;
  return options;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// The scenes hold the same triangles, positions, normals, texture coordinates and materials, bit for bit and in
/// the same order, and the loads gave the same warnings.
void expect_same(const LoadedScene& expected, const LoadedScene& got, const std::string& what) {
  const Scene& a = expected.scene;
  const Scene& b = got.scene;
  EXPECT_TRUE(same_bytes(a.positions, b.positions)) << what << ": positions";
  EXPECT_TRUE(same_bytes(a.normals, b.normals)) << what << ": normals";
  EXPECT_TRUE(same_bytes(a.texcoords, b.texcoords)) << what << ": texture coordinates";
  EXPECT_TRUE(same_bytes(a.triangles, b.triangles)) << what << ": triangles";
  EXPECT_EQ(a.emitters, b.emitters) << what;
  ASSERT_EQ(a.materials.size(), b.materials.size()) << what;
  for (size_t m = 0; m < a.materials.size(); ++m) {
    EXPECT_EQ(a.materials[m].name, b.materials[m].name) << what;
    EXPECT_EQ(a.materials[m].kd, b.materials[m].kd) << what;
    EXPECT_EQ(a.materials[m].ke, b.materials[m].ke) << what;
  }
  EXPECT_EQ(expected.warnings, got.warnings) << what;
}

void expect_chunking_changes_nothing(const std::string& obj, const std::string& mtl, const std::string& name) {
  const LoadedScene one = load_obj_from_text(obj, mtl, name, options_for(kOneChunk));
  for (const Schedule& s : kManyChunks)
    expect_same(one, load_obj_from_text(obj, mtl, name, options_for(s)),
                name + " in chunks of " + std::to_string(s.chunk_bytes) + " bytes on " + std::to_string(s.threads) +
                    " threads");
}

/// The message a load fails with ("" when it does not).
std::string error_of(const std::string& obj, const Schedule& schedule, std::optional<MemoryBudget> memory = {}) {
  LoadOptions options = options_for(schedule);
  options.memory = memory;
  try {
    load_obj_from_text(obj, "", "bad.obj", options);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

/// Lines of `v` and `f` statements: a strip of `quads` quads, enough text for many chunks.
std::string strip_of_quads(int quads) {
  std::string obj = "# a strip\n";
  for (int i = 0; i <= quads; ++i) {
    obj += "v " + std::to_string(i) + " 0 0\n";
    obj += "v " + std::to_string(i) + " 1 0.5\n";
  }
  for (int i = 0; i < quads; ++i) {
    const int a = 2 * i + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) + " " +
           std::to_string(a + 1) + "\n";
  }
  return obj;
}

TEST(ObjChunks, EveryStatementReadsTheSameInManyChunks) {
  // Negative indices reaching into earlier chunks, materials switched and named before and after the mtllib line,
  // polygons, normals and texture coordinates, comments, CRLF and lone-CR line ends, blank lines, lines and points.
  const std::string obj =
      "# header\r\nusemtl early\r\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\nf 1 2 3\n"
      "mtllib scene.mtl\nvt 0 0\nvt 1 0\nvt 1 1 0\nvt 0\nvn 0 0 1\nvn 0 0 2\nvn 0 0 0\n\n   \n"
      "usemtl red\nf 1/1/1 2/2/2 3/3/3 4/4/1\ng group\ns 1\no thing\nusemtl light\rf -5 -4 -3 -2 -1\r"
      "l 1 2\np 3\nusemtl missing\nf -5//-1 -4//-2 -3//-3\nusemtl red\n"
      "v 2 0 0\nv 3 0 0\nv 3 1 0\nv 2.5 0.5 0\nv 2 1 0\n  f  -5/-4  -4/-3  -3/-2  -2/-1  -1/-4\n";
  const std::string mtl = "newmtl red\nKd 0.8 0.1 0.1\nnewmtl light\nKd 0 0 0\nKe 4 4 4\n";
  expect_chunking_changes_nothing(obj, mtl, "statements.obj");
  // And what that scene is, so that the comparison above compares something.
  const Scene scene = load_obj_from_text(obj, mtl, "statements.obj", options_for({5, 3})).scene;
  EXPECT_EQ(scene.triangles.size(), 1u + 2u + 3u + 1u + 3u);
  EXPECT_EQ(scene.material_of(0).name, "default");  // named before the mtllib line: grey
  EXPECT_EQ(scene.material_of(1).name, "red");
  EXPECT_EQ(scene.material_of(3).name, "light");
  EXPECT_EQ(scene.material_of(6).name, "default");  // an unknown name
  const Triangle& relative = scene.triangles[6];    // -5 -4 -3 with five vertices so far
  EXPECT_EQ(relative.v[0], 0u);
  EXPECT_EQ(relative.v[1], 1u);
  EXPECT_EQ(relative.v[2], 2u);
  EXPECT_EQ(scene.material_of(9).name, "red");
  for (int t = 7; t < 10; ++t)  // the last pentagon's relative indices: the last five vertices
    for (uint32_t v : scene.triangles[t].v) EXPECT_GE(v, 5u);
}

TEST(ObjChunks, EveryIndexFormReadsAsWritten) {
  // The plain forms take a fast path and the rest (signs, zero padding past 9 digits) the general one: both must
  // read the same indices.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
      "f 1 2 3\nf 1/3 2/2 3/1\nf 1/1/1 2/3/1 3/2/1\nf 3//1 2//1 1//1\n"
      "f 001 +2 -1\nf 0000000001/0000000002 2/+3 3/-3\nf 1//+1 2//-1 3//0000000001\n";
  for (const unsigned threads : {1u, 2u}) {
    LoadOptions options;
    options.threads = threads;
    options.chunk_bytes = threads == 1 ? 0 : 16;
    const Scene scene = load_obj_from_text(obj, "", "forms.obj", options).scene;
    const uint32_t v[7][3] = {{0, 1, 2}, {0, 1, 2}, {0, 1, 2}, {2, 1, 0}, {0, 1, 2}, {0, 1, 2}, {0, 1, 2}};
    const uint32_t t[7][3] = {{kNoTexcoord, kNoTexcoord, kNoTexcoord},
                              {2, 1, 0},
                              {0, 2, 1},
                              {kNoTexcoord, kNoTexcoord, kNoTexcoord},
                              {kNoTexcoord, kNoTexcoord, kNoTexcoord},
                              {1, 2, 0},
                              {kNoTexcoord, kNoTexcoord, kNoTexcoord}};
    const bool normal[7] = {false, false, true, true, false, false, true};
    for (int f = 0; f < 7; ++f) {
      SCOPED_TRACE(f);
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(scene.triangles[f].v[c], v[f][c]);
        EXPECT_EQ(scene.triangles[f].t[c], t[f][c]);
        EXPECT_EQ(scene.triangles[f].n[c] != kNoNormal, normal[f]);
      }
    }
  }
}

TEST(ObjChunks, LargeFilesReadTheSameInManyChunks) {
  expect_chunking_changes_nothing(strip_of_quads(3000), "", "strip.obj");
  // The default scene as a file (its materials, emitters and file normals).
  const std::string dir = test::make_temp_dir("obj-chunks");
  Scene scene = make_default_scene();
  compute_smooth_normals(scene);
  write_obj(scene, dir + "/default.obj");
  expect_chunking_changes_nothing(test::read_file(dir + "/default.obj"), test::read_file(dir + "/default.mtl"),
                                  "default.obj");
}

TEST(ObjChunks, TheSharedScenesReadTheSameInManyChunks) {
  if (test::shared_scene("README.md").empty()) GTEST_SKIP() << "../shared/scenes not present";
  namespace fs = std::filesystem;
  size_t scenes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(test::shared_scene(""))) {
    if (entry.path().extension() != ".obj") continue;
    const std::string path = entry.path().string();
    const LoadedScene one = load_obj(path, options_for(kOneChunk));
    for (const Schedule& s : {Schedule{4096, 3}, Schedule{100000, 2}, Schedule{0, 0}})
      expect_same(one, load_obj(path, options_for(s)), path + " in chunks of " + std::to_string(s.chunk_bytes));
    ++scenes;
  }
  EXPECT_GE(scenes, 6u);
}

TEST(ObjChunks, AnErrorInTheLastChunkNamesItsLine) {
  const std::string good = strip_of_quads(500);
  const auto lines_of = [](const std::string& text) { return std::count(text.begin(), text.end(), '\n'); };
  struct Case {
    std::string bad_line;
    std::string expected;  ///< what the message says after "bad.obj:LINE: "
  };
  // Refused by the line alone, by the counts of all the chunks before it, and by the budget of the whole file.
  const std::vector<Case> cases = {
      {"v 1 2 abc", "vertex coordinate 'abc' is not a number"},
      {"f 1 2 1003", "face index 1003 out of range (file has 1002 vertices so far)"},
      {"f -1 -2 -1003", "face index -1003 out of range (file has 1002 vertices so far)"},
      {"f 1/1 2 3", "face texture index 1 out of range (file has 0 texture coordinates so far)"},
      {"usemtl x\x01", "binary data (byte 0x01): not an OBJ text file"},
      {"bogus 1 2", "unknown statement 'bogus'"},
  };
  for (const Case& c : cases) {
    // The bad line in the middle of the last chunk of many, with good lines after it.
    const std::string obj = good + "f 1 2 3\n" + c.bad_line + "\nf 1 2 3\nf 2 3 4\n";
    const std::string expected = "bad.obj:" + std::to_string(lines_of(good) + 2) + ": " + c.expected;
    EXPECT_EQ(error_of(obj, kOneChunk), expected);
    for (const Schedule& s : kManyChunks) EXPECT_EQ(error_of(obj, s), expected) << "chunks of " << s.chunk_bytes;
  }
  // Two bad lines in different chunks: the first in the file is named, whichever thread met its chunk first.
  const std::string two = "v 0 0 0\nf 1 1 7\n" + good + "v x\n";
  for (const Schedule& s : kManyChunks)
    EXPECT_EQ(error_of(two, s), "bad.obj:2: face index 7 out of range (file has 1 vertices so far)");
}

TEST(ObjChunks, TheMemoryBudgetNamesTheSameLine) {
  const std::string obj = strip_of_quads(2000);
  const MemoryBudget budget{400'000, "a test budget"};
  const std::string expected = error_of(obj, kOneChunk, budget);
  ASSERT_NE(expected.find("scene too large"), std::string::npos) << expected;
  ASSERT_EQ(expected.rfind("bad.obj:", 0), 0u) << expected;
  for (const Schedule& s : kManyChunks) EXPECT_EQ(error_of(obj, s, budget), expected) << "chunks of " << s.chunk_bytes;
}

}  // namespace
}  // namespace lueur
