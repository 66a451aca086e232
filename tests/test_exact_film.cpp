// The film's exact sums: any split of the frames (threads, MPI ranks, resumed runs) gives the same bytes, samples
// too large or not finite are dropped whole, and the unit follows the brightest emission.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <stdexcept>

#include "integrator/renderer.h"
#include "runtime/resume_state.h"
#include "scene/default_scene.h"

namespace lueur {
namespace {

std::shared_ptr<const TracedScene> default_traced() {
  Scene scene = make_default_scene();
  compute_smooth_normals(scene);
  return prepare_scene(std::move(scene));
}

RenderSettings small_settings() {
  RenderSettings settings;
  settings.width = 37;  // not a multiple of the tile size
  settings.height = 29;
  settings.l1_rays = 2;
  settings.l2_rays = 2;
  settings.ln_rays = 1;
  settings.enabled = {true, true, true, true, true};
  return settings;
}

bool same_bytes(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TEST(ExactFilm, AnySplitOfTheFramesGivesTheSameBytes) {
  const auto traced = default_traced();
  const RenderSettings settings = small_settings();
  const Camera camera = make_camera(default_scene_camera(), settings.width, settings.height);
  constexpr uint64_t kFrames = 11;

  Film whole;
  whole.reset(settings);
  ThreadPool two(2);
  for (uint64_t f = 0; f < kFrames; ++f) render_frame(*traced, camera, settings, whole, nullptr, two);

  // Three "ranks" of 1, 2 and 3 threads share each round's frames (rounds end at powers of two, as lueur-mpi's do);
  // each keeps its own exact sums across rounds and hands them over at the round's end.
  std::array<ThreadPool, 3> pools{ThreadPool(1), ThreadPool(2), ThreadPool(3)};
  std::array<Film, 3> ranks;
  for (Film& rank : ranks) {
    rank.mode = FilmMode::kExactOnly;
    rank.reset(settings);
  }
  Film combined;
  combined.reset(settings);
  combined.unit = film_unit(*traced, camera, settings);
  const uint64_t round_ends[] = {1, 2, 4, 8, kFrames};
  uint64_t start = 0;
  for (const uint64_t end : round_ends) {
    // Uneven shares, the last rank's first: the order of the frames does not matter either.
    const uint64_t count = end - start;
    const uint64_t shares[3] = {count / 2, count - count / 2 - count / 4, count / 4};
    uint64_t next = start;
    for (int r = 2; r >= 0; --r) {
      Film& rank = ranks[static_cast<size_t>(r)];
      rank.frames = next;
      for (uint64_t f = 0; f < shares[r]; ++f)
        render_frame(*traced, camera, settings, rank, nullptr, pools[static_cast<size_t>(r)]);
      next += shares[r];
    }
    ASSERT_EQ(next, end);
    ExactSums round = ranks[0].exact;
    for (int r = 1; r < 3; ++r)
      for (size_t l = 0; l < kLayerCount; ++l)
        for (size_t i = 0; i < round[l].size(); ++i) round[l][i] += ranks[static_cast<size_t>(r)].exact[l][i];
    for (Film& rank : ranks)
      for (auto& layer : rank.exact) std::fill(layer.begin(), layer.end(), 0);
    combined.add_exact(round, end);
    start = end;
  }

  ASSERT_EQ(combined.frames, whole.frames);
  for (size_t l = 0; l < kLayerCount; ++l) {
    EXPECT_EQ(combined.exact[l], whole.exact[l]) << kLayerNames[l];
    EXPECT_TRUE(same_bytes(combined.sums[l], whole.sums[l])) << kLayerNames[l];
  }
  for (size_t c = 0; c < kNoiseCheckpoints; ++c) {
    EXPECT_EQ(combined.checkpoints[c].frames, whole.checkpoints[c].frames);
    for (size_t p = 0; p < kPassCount; ++p)
      EXPECT_TRUE(same_bytes(combined.checkpoints[c].sums[p], whole.checkpoints[c].sums[p])) << c << " " << p;
  }
  // Not a vacuous equality: every pass has light in it.
  for (size_t p = 0; p < kPassCount; ++p) {
    double total = 0.0;
    for (const float v : whole.sums[p]) total += v;
    EXPECT_GT(total, 0.0) << kPassNames[p];
  }
}

TEST(ExactFilm, AddingFramesMustNotSkipAPowerOfTwo) {
  RenderSettings settings = small_settings();
  Film film;
  film.reset(settings);
  film.unit = 0x1p-32;
  const ExactSums none = film.exact;
  EXPECT_THROW(film.add_exact(none, 3), std::logic_error);  // 1 and 2 skipped
  film.add_exact(none, 1);
  film.add_exact(none, 2);
  film.add_exact(none, 4);
  EXPECT_THROW(film.add_exact(none, 9), std::logic_error);  // 8 skipped
  film.add_exact(none, 7);
  EXPECT_EQ(film.frames, 7u);
  EXPECT_EQ(film.checkpoints[0].frames, 4u);
  EXPECT_EQ(film.checkpoints[1].frames, 2u);
  EXPECT_THROW(film.add_exact(none, 6), std::logic_error);  // backwards
}

TEST(ExactFilm, SumsFromElsewhereThatWouldOverflowAreRefusedWhole) {
  // A reduction or a resumed state adds sums rendered elsewhere: one that would pass 64 bits (a corrupt or hostile
  // part) is refused, leaving the film as it was, rather than wrapping around to a sum of the other sign.
  RenderSettings settings = small_settings();
  Film film;
  film.reset(settings);
  film.unit = 0x1p-32;
  ExactSums part = film.exact;
  const size_t last = part[0].size() - 1;
  film.exact[0][last] = std::numeric_limits<int64_t>::max() - 3;
  part[0][0] = 7;     // fits
  part[0][last] = 5;  // overflows
  const ExactSums before = film.exact;
  EXPECT_THROW(film.add_exact(part, 1), std::overflow_error);
  EXPECT_EQ(film.exact, before);
  EXPECT_EQ(film.frames, 0u);
  part[0][last] = 3;  // exactly the largest sum
  film.add_exact(part, 1);
  EXPECT_EQ(film.exact[0][last], std::numeric_limits<int64_t>::max());
  EXPECT_EQ(film.exact[0][0], 7);
}

/// A state of `source`, decoded into a fresh accumulation of the same settings.
void decode_into_fresh(const Accumulation& source, const RenderSettings& settings) {
  const RenderIdentity identity = {"--test"};
  Accumulation restored;
  restored.reset(settings);
  decode_resume_state(encode_resume_state(identity, {&source}), identity, {&restored});
}

TEST(ResumeState, AUnitOrSnapshotsNoFilmCouldHoldAreRefused) {
  const auto traced = default_traced();
  RenderSettings settings = small_settings();
  settings.width = settings.height = 8;
  const Camera camera = make_camera(default_scene_camera(), settings.width, settings.height);
  ThreadPool pool(1);
  Accumulation rendered;
  rendered.reset(settings);
  for (int f = 0; f < 5; ++f) render_frame(*traced, camera, settings, rendered, pool);
  ASSERT_EQ(rendered.film.checkpoints[0].frames, 4u);
  EXPECT_NO_THROW(decode_into_fresh(rendered, settings));  // as written: frames 5, snapshots at 4, 2, 1

  const auto refused = [&](const Accumulation& altered, const std::string& message) {
    try {
      decode_into_fresh(altered, settings);
      ADD_FAILURE() << "accepted; expected: " << message;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  };
  Accumulation odd_unit = rendered;
  odd_unit.film.unit = 0.3 * rendered.film.unit;  // positive and finite, but no power of two
  refused(odd_unit, "impossible film unit");
  Accumulation infinite_unit = rendered;
  infinite_unit.film.unit = std::numeric_limits<double>::infinity();
  refused(infinite_unit, "impossible film unit");
  Accumulation late_snapshot = rendered;
  late_snapshot.film.checkpoints[0].frames = 8;  // past the 5 frames the film holds
  refused(late_snapshot, "impossible frame counts");
  Accumulation odd_snapshot = rendered;
  odd_snapshot.film.checkpoints[1].frames = 3;  // not a power of two, not half the newest
  refused(odd_snapshot, "impossible frame counts");
}

TEST(ExactFilm, ARenderThatKnowsItsLastFrameSkipsOnlySnapshotsItNeverReads) {
  EXPECT_EQ(needed_snapshots_from(0), 0u);
  EXPECT_EQ(needed_snapshots_from(7), 0u);  // 4, 2, 1: all kept
  EXPECT_EQ(needed_snapshots_from(10), 1u);
  EXPECT_EQ(needed_snapshots_from(64), 8u);
  EXPECT_EQ(needed_snapshots_from(100), 8u);
  EXPECT_EQ(needed_snapshots_from(128), 16u);
  // Frames 0-99 in rounds that skip 1, 2 and 4 end with the snapshots of 100 frames rendered one by one.
  RenderSettings settings = small_settings();
  Film skipping, sequential;
  skipping.reset(settings);
  sequential.reset(settings);
  skipping.unit = sequential.unit = 0x1p-32;
  const ExactSums none = skipping.exact;
  EXPECT_THROW(skipping.add_exact(none, 9, 8), std::logic_error);  // 8 is needed
  EXPECT_THROW(skipping.add_exact(none, 17, 8), std::logic_error);
  for (const uint64_t end : {8, 13, 16, 32, 50, 64, 100}) skipping.add_exact(none, end, 8);
  for (uint64_t f = 1; f <= 100; ++f) sequential.add_exact(none, f);
  for (size_t c = 0; c < kNoiseCheckpoints; ++c)
    EXPECT_EQ(skipping.checkpoints[c].frames, sequential.checkpoints[c].frames);
}

TEST(ExactFilm, SamplesTooLargeOrNotFiniteAreDroppedWhole) {
  RenderSettings settings;
  settings.width = 4;
  settings.height = 1;
  settings.enabled = {false, true, false, false};
  Film film;
  film.reset(settings);
  film.unit = 0x1p-32;
  std::array<std::vector<Vec3>, kLayerCount> values;
  const float too_large = static_cast<float>(kMaxSampleUnits * film.unit * 2.0);
  values[static_cast<size_t>(Layer::kL1)] = {Vec3(0.25f, 0.5f, 1.0f), Vec3(1.0f, NAN, 1.0f), Vec3(1.0f, 1.0f, INFINITY),
                                             Vec3(too_large, 1.0f, 1.0f)};
  EXPECT_EQ(film.add_frame(values), 3u);
  const std::vector<float>& l1 = film.sums[static_cast<size_t>(Layer::kL1)];
  EXPECT_EQ(l1[0], 0.25f);
  EXPECT_EQ(l1[1], 0.5f);
  EXPECT_EQ(l1[2], 1.0f);
  for (size_t i = 3; i < l1.size(); ++i) EXPECT_EQ(l1[i], 0.0f) << i;  // nothing of a dropped pixel is added
  // The largest sample accepted still sums exactly with small ones.
  values[static_cast<size_t>(Layer::kL1)] = {Vec3(0.0f), Vec3(static_cast<float>(kMaxSampleUnits * film.unit)),
                                             Vec3(0.0f), Vec3(0.0f)};
  EXPECT_EQ(film.add_frame(values), 0u);
  EXPECT_EQ(film.exact[static_cast<size_t>(Layer::kL1)][3], static_cast<int64_t>(kMaxSampleUnits));
}

TEST(ExactFilm, TheUnitIsAPowerOfTwoBelowTheBrightestEmissionBy32Bits) {
  const auto traced = default_traced();
  RenderSettings settings = small_settings();
  const Camera camera = make_camera(default_scene_camera(), settings.width, settings.height);
  float brightest = 1.0f;
  for (const EmitterRecord& e : traced->lights.records) brightest = std::max({brightest, e.ke.r, e.ke.g, e.ke.b});
  const double unit = film_unit(*traced, camera, settings);
  int exponent = 0;
  EXPECT_EQ(std::frexp(unit, &exponent), 0.5);  // a power of two
  EXPECT_GT(unit * 0x1p32, brightest);
  EXPECT_LE(unit * 0x1p31, brightest);
  settings.camera_light = true;  // the head-light is far brighter than the box's lamp
  EXPECT_GT(film_unit(*traced, camera, settings), unit);
}

}  // namespace
}  // namespace lueur
