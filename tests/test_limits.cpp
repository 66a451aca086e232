// Limits: work too large for the machine's memory is refused up front with a message that says so (image sizes,
// scene files and their vertex and triangle counts), and the memory budget behind that is read correctly.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>

#include "core/memory_budget.h"
#include "integrator/renderer.h"
#include "runtime/render_memory.h"
#include "scene/obj_loader.h"
#include "test_support.h"

namespace lueur {
namespace {

using test::ScopedEnv;

TEST(MemoryBudget, ParsesMemAvailable) {
  EXPECT_EQ(parse_meminfo_available("MemTotal:       24683620 kB\nMemFree:  100 kB\nMemAvailable:   2048 kB\n"),
            uint64_t{2048} * 1024);
  EXPECT_EQ(parse_meminfo_available("MemAvailable: 7 kB"), uint64_t{7} * 1024);
  EXPECT_FALSE(parse_meminfo_available("MemTotal: 10 kB\n"));
  EXPECT_FALSE(parse_meminfo_available("MemAvailable: lots\n"));
  EXPECT_FALSE(parse_meminfo_available("MemAvailable: 12 pages\n"));
  EXPECT_FALSE(parse_meminfo_available("XMemAvailable: 12 kB\n"));
}

TEST(MemoryBudget, TheMachineHasSomeAndTheUserCanCapIt) {
  const MemoryBudget machine = available_memory();
  EXPECT_GT(machine.bytes, uint64_t{16} << 20) << machine.source;
  EXPECT_LT(machine.bytes, std::numeric_limits<uint64_t>::max()) << "no memory figure found at all";
  {
    ScopedEnv cap("LUEUR_MEMORY_LIMIT_MB", "3");
    const MemoryBudget capped = available_memory();
    EXPECT_EQ(capped.bytes, uint64_t{3} << 20);
    EXPECT_EQ(capped.source, "LUEUR_MEMORY_LIMIT_MB");
  }
  for (const char* bad : {"0", "-5", "lots", "12MB", "99999999999999999999"}) {
    ScopedEnv cap("LUEUR_MEMORY_LIMIT_MB", bad);
    EXPECT_THROW(available_memory(), std::invalid_argument) << bad;
  }
}

TEST(MemoryBudget, FormatsBytesForMessages) {
  EXPECT_EQ(format_bytes(512), "512 bytes");
  EXPECT_EQ(format_bytes(1536), "1.5 KiB");
  EXPECT_EQ(format_bytes(uint64_t{3} << 30), "3.0 GiB");
  EXPECT_EQ(format_bytes(std::numeric_limits<uint64_t>::max()), "16.0 EiB");
}

TEST(RenderMemory, GrowsWithPixelsAndLayers) {
  RenderSettings small;
  small.width = small.height = 16;
  RenderSettings big = small;
  big.width = big.height = 1024;
  EXPECT_GT(render_memory_bytes(big), render_memory_bytes(small));
  RenderSettings all_passes = big;
  all_passes.enabled = {true, true, true, true};
  EXPECT_GT(render_memory_bytes(all_passes), render_memory_bytes(big));
  // At least the film itself: 3 floats per pixel and layer.
  const uint64_t pixels = 1024 * 1024;
  EXPECT_GE(render_memory_bytes(all_passes), pixels * 7 * 12);
  RenderSettings largest = all_passes;
  largest.width = largest.height = 16384;
  EXPECT_GT(render_memory_bytes(largest), uint64_t{60} << 30);
}

TEST(SceneMemory, NeverWrapsAround) {
  const uint64_t huge = std::numeric_limits<uint64_t>::max() / 2;
  EXPECT_EQ(scene_memory_bytes(huge, 0, 0, 0, 0), std::numeric_limits<uint64_t>::max());
  EXPECT_EQ(scene_memory_bytes(1, 1, 1, 1, huge), std::numeric_limits<uint64_t>::max());
  EXPECT_LT(scene_memory_bytes(1000, 10, 0, 0, 10), uint64_t{1} << 20);
}

std::string grid_obj(int n) {
  std::string obj;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      obj += "v ";
      obj += std::to_string(i);
      obj += ' ';
      obj += std::to_string(j);
      obj += " 0\n";
    }
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + n + 1) + " " +
             std::to_string(a + n) + "\n";
    }
  return obj;
}

TEST(SceneBudget, TooManyVerticesForTheBudgetIsRefusedAtTheLine) {
  const std::string obj = grid_obj(100);  // 10000 vertices, 19602 triangles
  LoadOptions options;
  EXPECT_EQ(load_obj_from_text(obj, "", "grid.obj", options).scene.triangles.size(), 19602u + 12u);
  options.memory = MemoryBudget{scene_memory_bytes(obj.size(), 5000, 0, 0, 0), "a test budget"};
  try {
    load_obj_from_text(obj, "", "grid.obj", options);
    ADD_FAILURE() << "loaded a scene over its budget";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    // Vertex 5001 is on line 5001: the first one over the budget.
    EXPECT_EQ(
        message.rfind("grid.obj:5001: scene too large: 5001 vertices and 0 triangles by this line need about ", 0), 0u)
        << message;
    EXPECT_NE(message.find("available (a test budget)"), std::string::npos) << message;
  }
}

TEST(SceneBudget, TooManyTrianglesForTheBudgetIsRefusedAtTheLine) {
  const std::string obj = grid_obj(100);  // 10000 vertex lines, then quads: two triangles a line
  LoadOptions options;
  options.memory = MemoryBudget{scene_memory_bytes(obj.size(), 10000, 0, 0, 1001), "a test budget"};
  for (const unsigned threads : {1u, 2u}) {
    options.threads = threads;
    try {
      load_obj_from_text(obj, "", "grid.obj", options);
      ADD_FAILURE() << "loaded a scene over its budget";
    } catch (const SceneError& e) {
      // The 501st quad brings 1002 triangles, one more than the budget holds.
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("grid.obj:10501: scene too large: 10000 vertices and 1002 triangles by this line", 0), 0u)
          << message;
    }
  }
}

TEST(SceneBudget, EmittersCountOnceTheMaterialsSayWhichTrianglesEmit) {
  // The same grid twice: lit by its own material (every triangle an emitter) and not.
  const std::string obj = "mtllib grid.mtl\nusemtl lamp\n" + grid_obj(60);  // 3600 vertices, 6962 triangles
  const std::string lamp = "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n", plain = "newmtl lamp\nKd 0.5 0.5 0.5\n";
  const uint64_t geometry = scene_memory_bytes(obj.size(), 3600, 0, 0, 6962);
  const uint64_t lights = emitter_memory_bytes(6962);
  EXPECT_GT(lights, 6962u * 345u) << "below what light sampling was measured to take per emitter";
  LoadOptions options;
  // A budget that holds the geometry but not its emitters: the plain grid loads, the lit one is refused.
  options.memory = MemoryBudget{geometry + lights / 2, "a test budget"};
  EXPECT_LT(load_obj_from_text(obj, plain, "grid.obj", options).scene.emitters.size(), 100u)
      << "only the default light rig's few";
  try {
    load_obj_from_text(obj, lamp, "grid.obj", options);
    ADD_FAILURE() << "loaded a scene whose emitters go over its budget";
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("grid.obj: scene too large: its 6962 emitting triangles (light sampling's", 0), 0u)
        << message;
    EXPECT_NE(message.find("available (a test budget)"), std::string::npos) << message;
  }
  options.memory = MemoryBudget{geometry + lights, "a test budget"};
  EXPECT_EQ(load_obj_from_text(obj, lamp, "grid.obj", options).scene.emitters.size(), 6962u);
  EXPECT_EQ(emitter_memory_bytes(std::numeric_limits<uint64_t>::max()), std::numeric_limits<uint64_t>::max());
}

TEST(SceneBudget, AFileLargerThanTheBudgetIsRefusedBeforeReading) {
  const std::string dir = test::make_temp_dir("limits-file");
  const std::string path = dir + "/big.obj";
  std::ofstream(path) << grid_obj(50);
  LoadOptions options;
  options.memory = MemoryBudget{1000, "a test budget"};
  try {
    load_obj(path, options);
    ADD_FAILURE() << "loaded a file over its budget";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": scene too large: a "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(" file needs about "), std::string::npos) << e.what();
  }
}

TEST(CliLimits, ImageLargerThanTheMemoryCapIsRefusedUpFront) {
  const std::string dir = test::make_temp_dir("limits-cli");
  const std::string out = dir + "/big.exr";
  const test::CommandResult r = test::run_lueur(
      "--headless --size 4096x4096 --frames 1 --out " + test::shell_quote(out), "LUEUR_MEMORY_LIMIT_MB=100");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("lueur: error: --size 4096x4096: rendering needs about "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("more than the 100.0 MiB available (LUEUR_MEMORY_LIMIT_MB)"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("frame 1/1"), std::string::npos) << "refused after rendering: " << r.output;
  EXPECT_FALSE(test::file_exists(out));

  // The same cap leaves room for a small image.
  const test::CommandResult ok =
      test::run_lueur("--headless --size 32x32 --frames 1 --l1-rays 1 --l2-rays 1 --out " + test::shell_quote(out),
                      "LUEUR_MEMORY_LIMIT_MB=100");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

TEST(SampleSequences, FramesBeforeTheyRepeatFollowTheLongestRunAFrameTakes) {
  RenderSettings settings;  // Le 4, L1 16, L2 16 with 2 recompute rays: L2's run is 16 x 2 samples a frame
  EXPECT_EQ(frames_before_samples_repeat(settings), (uint64_t{1} << 32) / 32);
  settings.reuse = ReuseMode::kCache;  // a bounce may fill the store with kL1CacheFillRays
  EXPECT_EQ(frames_before_samples_repeat(settings), (uint64_t{1} << 32) / (16 * 8));
  // The example: 4096 bounce rays, each with a run of 64 shadow samples: 2^18 a frame, 2^14 frames.
  settings.reuse = ReuseMode::kFrame;
  settings.l2_rays = 4096;
  settings.l1_rays = 64;
  settings.recompute_ratio = 1.0f;
  EXPECT_EQ(frames_before_samples_repeat(settings), uint64_t{16384});
  settings.l2_rays = 3000;  // runs are powers of two
  EXPECT_EQ(frames_before_samples_repeat(settings), uint64_t{16384});
  settings.enabled = {true, true, false, true};  // without L2, the longest run is L1's (or AO's) own
  settings.ao_rays = 1000;
  EXPECT_EQ(frames_before_samples_repeat(settings), (uint64_t{1} << 32) / 1024);
}

TEST(CliLimits, ARenderWhoseSamplesWouldRepeatIsRefusedUpFront) {
  // Frames past 2^32 samples of a pixel's sequence would repeat earlier ones: the image would stop converging.
  const std::string dir = test::make_temp_dir("limits-samples");
  const std::string out = dir + "/repeat.pfm";
  const std::string rays = "--headless --size 4x4 --l2-rays 4096 --l1-rays 64 --recompute-ratio 1 --out " +
                           test::shell_quote(out);
  const test::CommandResult r = test::run_lueur(rays + " --frames 16385");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("lueur: error: --frames 16385: at these ray counts each pixel's sample sequence (2^32 "
                          "samples) starts over after 16384 frames"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(test::file_exists(out));
  // The right side of an A/B split is held to it too.
  const test::CommandResult split = test::run_lueur(
      "--headless --size 4x4 --frames 1000000 --compare l2-rays=4096 --out " + test::shell_quote(out));
  EXPECT_EQ(split.exit_code, 2) << split.output;
  EXPECT_NE(split.output.find("(the right side of --compare)"), std::string::npos) << split.output;
}

TEST(CliLimits, LargestImageIsRefusedWhereTheMachineCannotHoldIt) {
  RenderSettings largest;
  largest.width = largest.height = 16384;
  largest.enabled = {true, true, true, true};
  if (render_memory_bytes(largest) <= available_memory().bytes)
    GTEST_SKIP() << "this machine has room for a 16384x16384 render";
  const std::string dir = test::make_temp_dir("limits-machine");
  const test::CommandResult r = test::run_lueur("--headless --size 16384x16384 --passes le,l1,l2,ao --frames 1 --out " +
                                                test::shell_quote(dir + "/huge.exr"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("rendering needs about "), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(dir + "/huge.exr"));
}

TEST(CliLimits, SceneLargerThanWhatTheImageLeavesIsRefused) {
  const std::string dir = test::make_temp_dir("limits-scene");
  const std::string scene = dir + "/grid.obj";
  std::ofstream(scene) << grid_obj(300);  // 90000 vertices, about 2.3 MB
  const std::string out = dir + "/out.png";
  const test::CommandResult r =
      test::run_lueur(test::shell_quote(scene) + " --headless --size 16x16 --frames 1 --out " + test::shell_quote(out),
                      "LUEUR_MEMORY_LIMIT_MB=70");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("scene too large: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("less 64.2 MiB for the 16x16 image"), std::string::npos) << r.output;
  EXPECT_FALSE(test::file_exists(out));
}

}  // namespace
}  // namespace lueur
