// lueur-bench's plumbing, not its figures: a tiny run writes JSON in the issue's schema, and bad input is a
// one-line error with exit status 2. The figures themselves are not tested (they depend on the machine).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>

#include "accel/embree_backend.h"
#include "bench/bench_throughput.h"
#include "passes/render_settings.h"
#include "test_support.h"

namespace lueur {
namespace {

test::CommandResult run_bench(const std::string& arguments) {
  return test::run_program(LUEUR_BENCH_EXECUTABLE, arguments);
}

/// {"lueur": number > 0, "embree": number > 0, or null without Embree}
void expect_pair(const nlohmann::json& pair, const std::string& what) {
  ASSERT_TRUE(pair.is_object()) << what;
  ASSERT_TRUE(pair["lueur"].is_number()) << what;
  EXPECT_GT(pair["lueur"].get<double>(), 0.0) << what;
  if (embree_available()) {
    ASSERT_TRUE(pair["embree"].is_number()) << what;
    EXPECT_GT(pair["embree"].get<double>(), 0.0) << what;
  } else {
    EXPECT_TRUE(pair["embree"].is_null()) << what;
  }
}

/// The JSON of a `--smoke` run with `arguments`, which must succeed (else a test failure and null).
nlohmann::json smoke_run_json(const std::string& arguments) {
  const std::string path = test::make_temp_dir("bench") + "/bench.json";
  const test::CommandResult r = run_bench("--smoke " + arguments + " --json " + path);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  if (r.exit_code != 0) return nullptr;
  return nlohmann::json::parse(test::read_file(path));
}

TEST(Bench, FiguresAreTheMedianRoundSoOneLuckyRoundCannotLiftThem) {
  EXPECT_DOUBLE_EQ(bench::median({0.88, 0.87, 1.07, 0.89, 0.86}), 0.88);
  EXPECT_DOUBLE_EQ(bench::median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(bench::median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_DOUBLE_EQ(bench::median({5.0}), 5.0);
  EXPECT_DOUBLE_EQ(bench::median({}), 0.0);
}

TEST(Bench, SmokeRunWritesTheIssuesJsonSchema) {
  const nlohmann::json j = smoke_run_json("");
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.size(), 3u);

  // Two scenes (default, a small sphere field) x three kinds x (1 and all threads).
  const auto& results = j["results"];
  ASSERT_TRUE(results.is_array());
  EXPECT_GE(results.size(), 6u);
  std::set<std::string> kinds;
  for (const auto& e : results) {
    EXPECT_TRUE(e["scene"].is_string());
    EXPECT_GT(e["triangles"].get<int>(), 0);
    kinds.insert(e["rays"].get<std::string>());
    EXPECT_GE(e["threads"].get<int>(), 1);
    expect_pair(e["mrays"], "mrays");
    if (embree_available())
      EXPECT_NEAR(e["ratio"].get<double>(), e["mrays"]["lueur"].get<double>() / e["mrays"]["embree"].get<double>(),
                  1e-9);
    else
      EXPECT_TRUE(e["ratio"].is_null());
  }
  EXPECT_EQ(kinds, (std::set<std::string>{"primary", "shadow", "bounce"}));

  const auto& build = j["build"];
  ASSERT_EQ(build.size(), 2u);
  for (const auto& b : build) {
    EXPECT_EQ(b.size(), 5u);
    EXPECT_TRUE(b["scene"].is_string());
    EXPECT_GT(b["triangles"].get<int>(), 0);
    expect_pair(b["ms"], "ms");
    expect_pair(b["bytes_per_triangle"], "bytes_per_triangle");
    expect_pair(b["resident_bytes_per_triangle"], "resident_bytes_per_triangle");
    // What is kept while tracing holds at least what the queries read.
    EXPECT_GE(b["resident_bytes_per_triangle"]["lueur"].get<double>(), b["bytes_per_triangle"]["lueur"].get<double>());
    if (embree_available()) {
      EXPECT_GE(b["resident_bytes_per_triangle"]["embree"].get<double>(),
                b["bytes_per_triangle"]["embree"].get<double>());
    }
  }

  // Every light strategy and every reuse mode, each with an RMSE per measure.
  const auto& convergence = j["convergence"];
  ASSERT_EQ(convergence.size(), kLightStrategyNames.size() + kReuseModeNames.size());
  for (const auto& c : convergence) {
    EXPECT_GE(c["frames"].get<int>(), 1);
    ASSERT_TRUE(c["rmse"].is_object());
    ASSERT_TRUE(c["curve"].is_array());
    ASSERT_FALSE(c["curve"].empty());
    // The curve's last point is the figure reported, after every frame rendered.
    EXPECT_EQ(c["curve"].back()["frames"], c["frames"]);
    EXPECT_EQ(c["curve"].back()["rmse"], c["rmse"]);
    const auto& first = c["curve"].front()["rmse"];
    for (const auto& [measure, value] : c["rmse"].items()) {
      // A few frames against a long reference: an error that is there, and no larger than after the first frame
      // (the variants converge to the reference; all of them are unbiased but the reuse modes, whose bias is far
      // below one frame's noise).
      EXPECT_GT(value.get<double>(), 0.0) << measure;
      EXPECT_TRUE(std::isfinite(value.get<double>())) << measure;
      EXPECT_LE(value.get<double>(), first[measure].get<double>() * 1.0001) << measure << " of " << c["variant"];
    }
  }
}

TEST(Bench, StoreFramesSectionFollowsL2ByFramesPerMode) {
  const nlohmann::json j = smoke_run_json("--sections store-frames");
  const auto& runs = j["store_frames"];
  ASSERT_EQ(runs.size(), 8u);  // the smoke run: the default scene and the built-in room (no shared scenes), 4 modes
  for (const auto& e : runs) {
    EXPECT_TRUE(e["scene"] == "default" || e["scene"] == "room") << e["scene"];
    ASSERT_EQ(e["checkpoints"].size(), 1u);  // the smoke run's 64 frames: one power of two from 64
    EXPECT_EQ(e["checkpoints"][0]["frames"].get<int>(), 64);
    EXPECT_TRUE(std::isfinite(e["checkpoints"][0]["l2_mse"].get<double>()));
    EXPECT_GT(e["reference_noise"].get<double>(), 0.0);
    const bool store = e["reuse"] == "cache" || e["reuse"] == "screen+cache";
    // The store modes say how many samples the cells that served held: at least the ready count.
    EXPECT_EQ(e["served_cell_samples_median"].is_null(), !store) << e["reuse"];
    if (store) {
      EXPECT_GE(e["served_cell_samples_median"].get<int>(), 16) << e["reuse"];
    }
  }
}

TEST(Bench, StoreSectionRacesTheReuseModesAgainstAnUnbiasedReference) {
  const nlohmann::json j = smoke_run_json("--sections store");
  const auto& store = j["store"];
  ASSERT_EQ(store.size(), 4u);  // the smoke run has the default scene only
  std::set<std::string> modes;
  for (const auto& e : store) {
    EXPECT_EQ(e["scene"], "default");
    modes.insert(e["reuse"].get<std::string>());
    EXPECT_GE(e["frames"].get<int>(), 1);
    EXPECT_GT(e["l2_rmse"].get<double>(), 0.0);
    EXPECT_GT(e["image_rmse"].get<double>(), 0.0);
    // Where a mode reached `frame`'s final L2 error, it did so within its own run, after its first frame.
    if (!e["seconds_to_frame_l2_rmse"].is_null()) {
      EXPECT_GT(e["seconds_to_frame_l2_rmse"].get<double>(), 0.0) << e["reuse"];
      EXPECT_LE(e["seconds_to_frame_l2_rmse"].get<double>(), e["seconds"].get<double>()) << e["reuse"];
    }
    if (e["reuse"] == "cache" || e["reuse"] == "screen+cache") {
      EXPECT_GT(e["cache_cells"].get<int>(), 0);
    }
  }
  EXPECT_EQ(modes, (std::set<std::string>{"off", "frame", "cache", "screen+cache"}));
}

TEST(Bench, StoreSectionTakesTheStoresCellSize) {
  // The smoke run's 16-pixel images: automatic cells of 2 x sqrt(16 / 128) pixels, or the size asked for.
  for (const auto& [arguments, expected] :
       {std::pair<std::string, double>{"--sections store", 2.0 * std::sqrt(16.0 / 128.0)},
        {"--sections store --store-cell-pixels 8", 8.0}}) {
    const nlohmann::json j = smoke_run_json(arguments);
    for (const auto& e : j["store"]) {
      if (e["reuse"] == "cache" || e["reuse"] == "screen+cache")
        EXPECT_NEAR(e["cache_cell_pixels"].get<double>(), expected, 1e-5) << arguments;
      else
        EXPECT_TRUE(e["cache_cell_pixels"].is_null()) << arguments;
    }
  }
}

TEST(Bench, TraversalSectionCountsLueursWorkPerRay) {
  const nlohmann::json j = smoke_run_json("--sections traversal");
  ASSERT_TRUE(j.is_object());
  const auto& traversal = j["traversal"];
  ASSERT_TRUE(traversal.is_array());
  ASSERT_EQ(traversal.size(), 6u);  // two scenes x three kinds of rays
  for (const auto& e : traversal) {
    EXPECT_GT(e["triangles"].get<int>(), 0);
    // Every query tests the root's children; a leaf holds at least one group.
    EXPECT_GE(e["nodes_per_ray"].get<double>(), 1.0);
    EXPECT_GE(e["groups_per_ray"].get<double>(), e["leaves_per_ray"].get<double>());
  }
  EXPECT_TRUE(j["results"].empty());  // throughput was not asked for
}

TEST(Bench, FrameSectionCountsTheRenderersRaysByQuery) {
  const nlohmann::json j = smoke_run_json("--sections frame --only default");
  ASSERT_TRUE(j.is_object());
  const auto& frames = j["frames"];
  ASSERT_TRUE(frames.is_array());
  ASSERT_FALSE(frames.empty());
  for (const auto& f : frames) {
    EXPECT_EQ(f["scene"], "default");
    const int count = f["frames"].get<int>();
    EXPECT_GE(count, 2);
    // Per pixel of the 24 x 24 smoke view per frame, the camera ray that shades (up to 16 bounce rays at its hit,
    // and the shadow rays of 16 L1 samples there plus 2 at each recomputed bounce hit) and `le_rays` more for Le.
    const auto le_rays = static_cast<uint64_t>(RenderSettings{}.le_rays);
    ASSERT_GT(le_rays, 1u);
    const auto primary = f["rays"]["primary"].get<uint64_t>(), bounce = f["rays"]["bounce"].get<uint64_t>(),
               any_hit = f["rays"]["any_hit"].get<uint64_t>();
    const uint64_t shaded = static_cast<uint64_t>(count) * 24u * 24u;
    EXPECT_EQ(primary, shaded * (1 + le_rays));
    EXPECT_GT(bounce, shaded);
    EXPECT_LE(bounce, 16u * shaded);
    EXPECT_GT(any_hit, shaded);
    EXPECT_LE(any_hit, (16u + 16u * 2u) * shaded);
    EXPECT_GT(f["renderer_mrays"].get<double>(), 0.0);
    EXPECT_GT(f["arrays_mrays"].get<double>(), 0.0);
  }
  // The comparison needs the arrays' throughput: it was measured even though only the frame section was asked for.
  EXPECT_FALSE(j["results"].empty());
}

TEST(Bench, BadInputIsOneLineAndStatusTwo) {
  for (const std::string args : {"--no-such-option", "--sections build,nonsense", "--json /no/such/dir/b.json",
                                 "--store-cell-pixels -1", "--store-conference-light sky"}) {
    const test::CommandResult r = run_bench(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << ": " << r.output;
    EXPECT_EQ(r.output.rfind("lueur-bench: error: ", 0), 0u) << r.output;
  }
}

}  // namespace
}  // namespace lueur
