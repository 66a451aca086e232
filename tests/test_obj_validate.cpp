// The OBJ validator through load_obj: every malformed line is refused with a one-line "file:line: ..." message
// before tinyobjloader sees it, and long but valid input (megabyte lines, a face of 5000 vertices) still loads.
// Uses the scene layer only (no BVH, no renderer).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include "obj_test_support.h"
#include "scene/obj_loader.h"
#include "test_support.h"

namespace lueur {
namespace {

using test::expect_error;
using test::kTriangle;
using test::write_text;

// ---- bad input --------------------------------------------------------------------------------------------

TEST(SceneErrors, MissingFileAndDirectory) {
  const std::string dir = test::make_temp_dir("errors-files");
  expect_error(dir + "/nothing-here.obj", 0, "cannot open '" + dir + "/nothing-here.obj': No such file or directory");
  expect_error(dir, 0, "cannot open '" + dir + "': Is a directory");
  expect_error(write_text(dir, "empty.obj", ""), 0, "empty.obj: no triangles");
  expect_error(write_text(dir, "points.obj", "# only points\nv 0 0 0\nv 1 0 0\np 1 2\nl 1 2\n"), 0,
               "points.obj: no triangles");
  if (::geteuid() != 0) {  // root reads anything
    const std::string locked = write_text(dir, "locked.obj", kTriangle + "f 1 2 3\n");
    ::chmod(locked.c_str(), 0);
    expect_error(locked, 0, "Permission denied");
  }
}

TEST(SceneErrors, EachBadLineNamesFileAndLine) {
  const std::string dir = test::make_temp_dir("errors-lines");
  struct Case {
    const char* file;
    std::string text;
    size_t line;
    const char* fragment;
  };
  const std::string t = kTriangle;  // lines 1-3
  const Case cases[] = {
      {"garbage.obj", t + "f 1 2 3\nhello world\n", 5, "unknown statement 'hello'"},
      {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", 2, "'nan' is not a finite number"},
      {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n", 3, "'-inf' is not a finite number"},
      {"huge.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", 2, "'1e39' is not a finite number"},
      {"junk-number.obj", "v 0 0 0\nv 1.5abc 0 0\nv 0 1 0\nf 1 2 3\n", 2, "'1.5abc' is not a number"},
      {"short-vertex.obj", "v 0 0\n", 1, "vertex needs three coordinates"},
      {"out-of-range.obj", t + "\n# comment\nf 1 2 40\n", 6, "face index 40 out of range (file has 3 vertices so far)"},
      {"negative-out-of-range.obj", t + "f -1 -2 -4\n", 4, "face index -4 out of range"},
      {"forward.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", 3, "face index 3 out of range"},
      {"normal-range.obj", t + "vn 0 0 1\nf 1//1 2//2 3//1\n", 5, "face normal index 2 out of range"},
      {"texture-range.obj", t + "f 1/1 2/1 3/1\n", 4, "face texture index 1 out of range"},
      {"two-vertices.obj", t + "f 1 2\n", 4, "face has 2 vertices (needs at least 3)"},
      {"index-zero.obj", t + "f 0 1 2\n", 4, "face index 0"},
      {"not-integer.obj", t + "f 1 2 x\n", 4, "not an integer index"},
      {"float-index.obj", t + "f 1 2 3.5\n", 4, "not an integer index"},
      {"empty-last-slot.obj", t + "f 1/ 2 3\n", 4, "bad face vertex '1/' (not an integer index)"},
      {"empty-normal-slot.obj", t + "f 1// 2 3\n", 4, "bad face vertex '1//' (not an integer index)"},
      {"empty-vertex-slot.obj", t + "f /1 2 3\n", 4, "bad face vertex '/1' (not an integer index)"},
      {"four-slots.obj", t + "f 1/1/1/1 2 3\n", 4, "bad face vertex '1/1/1/1'"},
      {"ten-digits.obj", t + "f 1 2 1234567890\n", 4, "face index 1234567890 out of range"},
      {"zero-padded-zero.obj", t + "f 1 2 000\n", 4, "face index 0 in '000'"},
      {"signed-beyond.obj", t + "f 1 2 +4\n", 4, "face index +4 out of range (file has 3 vertices so far)"},
      {"binary.obj", t + "f 1 2 3\n\x7f" + "ELF" + std::string("\x02\x01\x01\0\0\0", 6) + "garbage", 5,
       "binary data (byte 0x7f)"},
      {"nul.obj", t + std::string("f 1 2 3\0\n", 9), 4, "binary data (byte 0x00)"},
      {"crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 9\r\n", 4, "face index 9 out of range"},
      {"lone-cr.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 9\r", 4, "face index 9 out of range"},
  };
  for (const Case& c : cases) expect_error(write_text(dir, c.file, c.text), c.line, c.fragment);

  // Pure binary garbage from the start.
  std::string noise(4096, '\0');
  std::mt19937 rng(7);
  for (char& ch : noise) ch = static_cast<char>(rng() & 0xff);
  expect_error(write_text(dir, "noise.obj", noise), 1, "binary data");
}

TEST(SceneErrors, CommittedSamples) {
  const std::string bad = std::string(LUEUR_TEST_SCENES) + "/bad/";
  expect_error(bad + "garbage_line.obj", 5, "unknown statement");
  expect_error(bad + "index_out_of_range.obj", 7, "face index 12 out of range (file has 4 vertices so far)");
  expect_error(bad + "nan_vertex.obj", 3, "is not a finite number");
}

TEST(SceneErrors, InMemoryTextUsesTheGivenName) {
  try {
    load_obj_from_text(kTriangle + "f 1 2 3 4\n", "", "memory.obj");
    ADD_FAILURE();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), "memory.obj:4: face index 4 out of range (file has 3 vertices so far)");
  }
}

// ---- size limits ------------------------------------------------------------------------------------------

TEST(SceneLimits, MegabyteLines) {
  std::string comment = "# " + std::string(1 << 20, 'x') + "\n";
  // A valid triangle face one megabyte long: indices with many leading zeros.
  const std::string zeros(350000, '0');
  std::string face = "f " + zeros + "1 " + zeros + "2 " + zeros + "3\n";
  ASSERT_GT(face.size(), 1000000u);
  const LoadedScene loaded = load_obj_from_text(comment + kTriangle + face + comment, "", "long.obj");
  ASSERT_EQ(loaded.scene.triangles.size(), 1u + 12u);  // and the light rig's sky
  EXPECT_EQ(loaded.scene.triangles[0].v[2], 2u);

  // One megabyte of blanks between tokens is fine too.
  const std::string spaced = kTriangle + "f 1" + std::string(1 << 20, ' ') + "2\t3\n";
  EXPECT_EQ(load_obj_from_text(spaced, "", "spaced.obj").scene.triangles.size(), 1u + 12u);
}

TEST(SceneLimits, FaceWithFiveThousandVertices) {
  const int n = 5000;
  std::ostringstream obj;
  obj.precision(9);
  for (int i = 0; i < n; ++i) {
    // A star-shaped (concave) polygon in the XY plane, counter-clockwise from +Z.
    const float a = 2.0f * kPi * static_cast<float>(i) / n;
    const float r = (i % 2) ? 0.8f : 1.0f;
    obj << "v " << r * std::cos(a) << " " << r * std::sin(a) << " 0\n";
  }
  obj << "f";
  for (int i = 1; i <= n; ++i) obj << " " << i;
  obj << "\n";
  // Ear clipping takes time growing with the square of the vertex count; the loader refuses faces too large to
  // triangulate in reasonable time (the hostile scenes check that), and this one is well within its limit.
  const LoadedScene loaded = load_obj_from_text(obj.str(), "", "polygon.obj");
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.triangles.size(), static_cast<size_t>(n - 2) + 12u);  // and the light rig's sky
  double area = 0.0;
  for (uint32_t t = 0; t < static_cast<uint32_t>(n - 2); ++t) {
    const Vec3 g = scene.geometric_normal_raw(t);
    EXPECT_GE(g.z, 0.0f) << "triangle " << t << " flipped";
    area += 0.5 * g.z;
  }
  // Area of the star: n/2 kites, each two triangles (1, 0.8) around the centre.
  const double expected = n * 0.5 * 1.0 * 0.8 * std::sin(2.0 * M_PI / n);
  EXPECT_NEAR(area, expected, 1e-3 * expected);
}

}  // namespace
}  // namespace lueur
