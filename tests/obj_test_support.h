// Helpers shared by the OBJ loader's test files (test_obj_*, test_smooth_normals, test_default_light,
// test_shared_scenes): writing OBJ/MTL text to disk, expecting a file:line error, reading warnings, a cube.
// Header-only, so that tests/CMakeLists.txt builds every suite the same way. Uses the scene layer and GoogleTest only.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "scene/obj_loader.h"
#include "scene/scene.h"

namespace lueur::test {

/// Three vertices, lines 1-3 of many test files: "f 1 2 3" after them is one triangle.
inline const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

/// Loader options without computed normals: every triangle shaded with its geometric normal.
inline LoadOptions flat_shading() {
  LoadOptions options;
  options.smooth_normals = false;
  return options;
}

/// Writes `text` to dir/name, byte for byte; returns the path.
inline std::string write_text(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

/// Loads `path` expecting a SceneError whose message starts with "path:line: " (line 0: "path: " or any
/// message naming the path) and contains `fragment`.
inline void expect_error(const std::string& path, size_t line, const std::string& fragment) {
  SCOPED_TRACE(path);
  try {
    load_obj(path);
    ADD_FAILURE() << "no SceneError for " << path;
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    if (line > 0) {
      EXPECT_EQ(message.rfind(path + ":" + std::to_string(line) + ": ", 0), 0u) << message;
    } else {
      EXPECT_NE(message.find(path), std::string::npos) << message;
    }
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

/// True when one of the loader's warnings contains `fragment`.
inline bool has_warning(const LoadedScene& loaded, const std::string& fragment) {
  for (const std::string& w : loaded.warnings) {
    if (w.find(fragment) != std::string::npos) return true;
  }
  return false;
}

/// Every warning, one indented line each: the failure message of a has_warning check.
inline std::string all_warnings(const LoadedScene& loaded) {
  std::string out;
  for (const std::string& w : loaded.warnings) out += "  " + w + "\n";
  return out;
}

inline Vec3 unit(const Vec3& v) { return glm::normalize(v); }

/// Number of triangles whose material is the given one.
inline size_t count_with_material(const Scene& scene, const std::string& name) {
  size_t n = 0;
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) n += scene.material_of(t).name == name;
  return n;
}

/// The unit cube [0, 1]^3 as six outward quads: indexed (eight shared vertices), or as a soup where every face
/// has its own copies of its corners, as exporters of triangle soups write them.
inline std::string cube_obj(bool soup) {
  const char* corners = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
  const int faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}};
  std::ostringstream obj;
  if (!soup) obj << corners;
  for (int f = 0; f < 6; ++f) {
    if (soup) {
      static const float p[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
      for (int k = 0; k < 4; ++k) {
        const float* q = p[faces[f][k] - 1];
        obj << "v " << q[0] << " " << q[1] << " " << q[2] << "\n";
      }
      obj << "f -4 -3 -2 -1\n";
    } else {
      obj << "f " << faces[f][0] << " " << faces[f][1] << " " << faces[f][2] << " " << faces[f][3] << "\n";
    }
  }
  return obj.str();
}

}  // namespace lueur::test
