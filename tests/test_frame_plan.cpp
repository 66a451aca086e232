// How lueur-mpi deals out frames: shares in proportion to speed that always add up, rounds that stop at every power
// of two of the frame count.
#include <gtest/gtest.h>

#include <numeric>

#include "runtime/frame_plan.h"

namespace lueur {
namespace {

uint64_t sum(const std::vector<uint64_t>& v) { return std::accumulate(v.begin(), v.end(), uint64_t{0}); }

TEST(FramePlan, SharesFollowTheRatesAndAddUp) {
  EXPECT_EQ(share_frames(12, {1.0, 1.0, 1.0}), (std::vector<uint64_t>{4, 4, 4}));
  EXPECT_EQ(share_frames(12, {1.0, 2.0, 3.0}), (std::vector<uint64_t>{2, 4, 6}));
  // Unknown rates count as the mean of the known ones, or all equal.
  EXPECT_EQ(share_frames(9, {0.0, 0.0, 0.0}), (std::vector<uint64_t>{3, 3, 3}));
  EXPECT_EQ(share_frames(8, {2.0, 0.0, 6.0, 0.0}), (std::vector<uint64_t>{1, 2, 3, 2}));
  // Remainders go to the largest fractions, ties to the lower rank.
  EXPECT_EQ(share_frames(2, {1.0, 1.0, 1.0}), (std::vector<uint64_t>{1, 1, 0}));
  EXPECT_EQ(share_frames(0, {1.0, 5.0}), (std::vector<uint64_t>{0, 0}));
  for (uint64_t count = 0; count < 200; count += 7) {
    const std::vector<double> rates = {0.3, 17.0, 2.5, 0.0, 9.1};
    const std::vector<uint64_t> shares = share_frames(count, rates);
    EXPECT_EQ(sum(shares), count);
    // No share is more than one frame from its exact proportion.
    for (size_t i = 0; i < rates.size(); ++i) {
      const double exact = static_cast<double>(count) * (rates[i] > 0 ? rates[i] : (0.3 + 17 + 2.5 + 9.1) / 4) /
                           (0.3 + 17 + 2.5 + 9.1 + (0.3 + 17 + 2.5 + 9.1) / 4);
      EXPECT_LT(std::abs(static_cast<double>(shares[i]) - exact), 1.0) << count << " " << i;
    }
  }
}

TEST(FramePlan, RoundsStopAtEveryPowerOfTwoAndAtTheEnd) {
  EXPECT_EQ(round_end(0, 100, 1000), 1u);
  EXPECT_EQ(round_end(1, 100, 1000), 2u);
  EXPECT_EQ(round_end(2, 100, 1000), 4u);
  EXPECT_EQ(round_end(5, 2, 1000), 7u);
  EXPECT_EQ(round_end(7, 2, 1000), 8u);
  EXPECT_EQ(round_end(600, 100, 1000), 700u);
  EXPECT_EQ(round_end(1000, 100, 1000), 1000u);
  EXPECT_EQ(round_end(990, 100, 1000), 1000u);
  EXPECT_EQ(round_end(3, 0, 1000), 4u);  // at least one frame
  // Walking the rounds reaches every power of two.
  std::vector<uint64_t> ends;
  for (uint64_t done = 0; done < 300; done = round_end(done, 50, 300)) ends.push_back(round_end(done, 50, 300));
  for (uint64_t p = 1; p <= 256; p *= 2) EXPECT_NE(std::find(ends.begin(), ends.end(), p), ends.end()) << p;
  EXPECT_EQ(ends.back(), 300u);
  // From `snapshots_from` on only: 1, 2 and 4 are passed when 8 is the lowest snapshot kept.
  EXPECT_EQ(round_end(0, 6, 100, 8), 6u);
  EXPECT_EQ(round_end(6, 6, 100, 8), 8u);
  EXPECT_EQ(round_end(0, 100, 100, 8), 8u);
}

TEST(FramePlan, ARoundGivesEachWorkerAboutTheSameTime) {
  // Unknown rates: one frame each, cut at the first stop (the power of two 1).
  EXPECT_EQ(plan_round(0, 100, 0, {0.0, 0.0}, 1.0), (std::vector<uint64_t>{1, 0}));
  EXPECT_EQ(plan_round(32, 100, 0, {0.0, 0.0, 0.0}, 1.0), (std::vector<uint64_t>{1, 1, 1}));
  // Known rates: a second of work each, 3 and 6 frames, even though 9 is odd.
  EXPECT_EQ(plan_round(33, 100, 0, {3.0, 6.0}, 1.0), (std::vector<uint64_t>{3, 6}));
  EXPECT_EQ(plan_round(33, 100, 0, {2.6, 2.6}, 1.0), (std::vector<uint64_t>{3, 3}));
  // Within two rounds of the next stop, the round goes to it, shared by rate: no short round is left behind.
  EXPECT_EQ(plan_round(46, 100, 0, {3.0, 6.0}, 1.0), (std::vector<uint64_t>{6, 12}));  // 18 frames to 64
  EXPECT_EQ(plan_round(28, 100, 0, {3.0, 6.0}, 1.0), (std::vector<uint64_t>{1, 3}));
  EXPECT_EQ(plan_round(96, 100, 0, {3.0, 6.0}, 1.0), (std::vector<uint64_t>{1, 3}));
  EXPECT_EQ(plan_round(100, 100, 0, {3.0, 6.0}, 1.0), (std::vector<uint64_t>{0, 0}));
  // A slow worker still gets a frame.
  EXPECT_EQ(plan_round(40, 100, 0, {0.1, 10.0}, 1.0), (std::vector<uint64_t>{1, 10}));
  // Walking the rounds of equal workers: every round but the first few (rates unknown, or cut at 1, 2, 4) is at
  // least a round's worth of work, and the rounds reach every stop.
  uint64_t done = 16;
  std::vector<uint64_t> ends;
  while (done < 1000) {
    const std::vector<uint64_t> shares = plan_round(done, 1000, 0, {5.0, 5.0}, 1.0);
    EXPECT_GE(sum(shares), 10u) << done;
    done += sum(shares);
    ends.push_back(done);
  }
  for (uint64_t p = 32; p <= 512; p *= 2) EXPECT_NE(std::find(ends.begin(), ends.end(), p), ends.end()) << p;
}

}  // namespace
}  // namespace lueur
