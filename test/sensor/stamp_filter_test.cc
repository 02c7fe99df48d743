#include "fusemap/sensor/stamp_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fusemap {
namespace sensor {
namespace {

constexpr int kLaser = 0, kOdometry = 1;
constexpr double kT0 = 1700000000.0;
using Verdict = StampFilter::Verdict;
using Held = StampFilter::Held;

StampFilter MakeFilter() { return StampFilter(StampFilterOptions(), 2, kLaser); }

// Issue 18 item 6: one odometry stamp 11.6 days ahead made every later one "going backwards".
TEST(StampFilterTest, OneStampFarAheadCostsOneMessage) {
  StampFilter filter = MakeFilter();
  int accepted = 0, rejected = 0, held = 0, dropped_held = 0;
  for (int i = 0; i < 1000; ++i) {
    const double stamp_s = kT0 + 0.02 * i + (i == 10 ? 11.6 * 86400.0 : 0.0);
    const auto d = filter.Check(kOdometry, stamp_s);
    accepted += d.verdict == Verdict::kAccept;
    rejected += d.verdict == Verdict::kReject;
    held += d.verdict == Verdict::kHold;
    dropped_held += d.held == Held::kDrop;
    if (i == 11) {
      EXPECT_NE(d.held_reason.find("outlier"), std::string::npos) << d.held_reason;
    }
  }
  EXPECT_EQ(accepted, 999);
  EXPECT_EQ(rejected, 0);
  EXPECT_EQ(held, 1);
  EXPECT_EQ(dropped_held, 1);
}

// Jumps are judged against every channel's newest stamp, so the first message of a channel
// cannot start it on an outlier's clock either.
TEST(StampFilterTest, FirstMessageOfAChannelJudgedAgainstTheOthers) {
  StampFilter filter = MakeFilter();
  EXPECT_EQ(filter.Check(kLaser, kT0).verdict, Verdict::kAccept);
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 1e6).verdict, Verdict::kHold);
  const auto d = filter.Check(kOdometry, kT0 + 0.01);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_EQ(d.held, Held::kDrop);
}

// A real jump of the clock (the robot's clock was corrected) is followed by the next message:
// the held one is released, nothing is lost.
TEST(StampFilterTest, JumpConfirmedByTheNextMessageReleasesTheHeldOne) {
  StampFilter filter = MakeFilter();
  EXPECT_EQ(filter.Check(kOdometry, kT0).verdict, Verdict::kAccept);
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 3600.0).verdict, Verdict::kHold);
  const auto d = filter.Check(kOdometry, kT0 + 3600.02);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_EQ(d.held, Held::kRelease);
  EXPECT_DOUBLE_EQ(d.held_stamp_s, kT0 + 3600.0);
  EXPECT_DOUBLE_EQ(d.stamp_s, kT0 + 3600.02);
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 3600.04).held, Held::kNone);
}

// Issue 18 item 7: utime -2^62 was taken as a time reset and shifted the run by 4.6e12 s.
TEST(StampFilterTest, AbsurdStampsAreMalformedNotTimeResets) {
  StampFilter filter = MakeFilter();
  EXPECT_EQ(filter.Check(kLaser, kT0).verdict, Verdict::kAccept);
  for (double bad : {-4.611686018427388e12, -1.0, 1e15, std::nan(""),
                     std::numeric_limits<double>::infinity()}) {
    const auto d = filter.Check(kLaser, bad);
    EXPECT_EQ(d.verdict, Verdict::kReject) << bad;
    EXPECT_EQ(d.kind, "absurd timestamp");
  }
  const auto d = filter.Check(kLaser, kT0 + 0.1);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_DOUBLE_EQ(d.stamp_s, kT0 + 0.1);
  EXPECT_EQ(filter.time_resets(), 0);
}

// A looping log player jumps back by the log's length: a time reset, applied at once.
TEST(StampFilterTest, PlausibleLaserLoopIsATimeReset) {
  StampFilter filter = MakeFilter();
  EXPECT_EQ(filter.Check(kLaser, kT0 + 300.0).verdict, Verdict::kAccept);
  const auto d = filter.Check(kLaser, kT0);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_TRUE(d.time_reset);
  EXPECT_DOUBLE_EQ(d.stamp_s, kT0 + 300.0 + StampFilter::kTimeResetGapS);
  EXPECT_EQ(filter.time_resets(), 1);
  // Odometry of the old loop, shifted like every stamp, lands 300 s ahead: held, and dropped
  // when the odometry of the new loop arrives on the new base.
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 299.0).verdict, Verdict::kHold);
  const auto next = filter.Check(kOdometry, kT0 + 0.05);
  EXPECT_EQ(next.held, Held::kDrop);
  EXPECT_NEAR(next.stamp_s, kT0 + 301.05, 1e-6);
}

// The end of one log loop (a scan at +300 s, odometry at +300.01 s), then the first odometry
// of the next loop, back at +0 s: held.
StampFilter FilterHoldingTheNewLoopsFirstOdometry() {
  StampFilter filter = MakeFilter();
  EXPECT_EQ(filter.Check(kLaser, kT0 + 300.0).verdict, Verdict::kAccept);
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 300.01).verdict, Verdict::kAccept);
  EXPECT_EQ(filter.Check(kOdometry, kT0).verdict, Verdict::kHold);
  return filter;
}

// A looping player may replay odometry before the first scan of the new loop: it was dropped
// as "going backwards" until the laser reset the time base. Held, and confirmed by the next
// odometry message on the new clock, it is the time reset; the laser follows on the new base.
TEST(StampFilterTest, OdometryOfTheNewLoopBeforeTheLaserIsKept) {
  StampFilter filter = FilterHoldingTheNewLoopsFirstOdometry();
  const auto d = filter.Check(kOdometry, kT0 + 0.02);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_EQ(d.held, Held::kRelease);
  EXPECT_TRUE(d.time_reset);
  EXPECT_NEAR(d.held_stamp_s, kT0 + 300.01 + StampFilter::kTimeResetGapS, 1e-6);
  EXPECT_NEAR(d.stamp_s, kT0 + 300.03 + StampFilter::kTimeResetGapS, 1e-6);
  const auto scan = filter.Check(kLaser, kT0 + 0.03);
  EXPECT_EQ(scan.verdict, Verdict::kAccept);
  EXPECT_FALSE(scan.time_reset);
  EXPECT_NEAR(scan.stamp_s, kT0 + 300.04 + StampFilter::kTimeResetGapS, 1e-6);
  EXPECT_EQ(filter.time_resets(), 1);
}

// The same, when the laser's first scan of the new loop comes between the two odometry
// messages: the laser resets, and the held odometry is released on the new base.
TEST(StampFilterTest, OdometryHeldUntilTheLaserResetsIsReleased) {
  StampFilter filter = FilterHoldingTheNewLoopsFirstOdometry();
  const auto scan = filter.Check(kLaser, kT0 + 0.01);
  EXPECT_TRUE(scan.time_reset);
  // After the newest stamp of any channel (the odometry's), not only the laser's.
  EXPECT_NEAR(scan.stamp_s, kT0 + 300.01 + StampFilter::kTimeResetGapS, 1e-6);
  const auto d = filter.Check(kOdometry, kT0 + 0.02);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_EQ(d.held, Held::kRelease);
  EXPECT_FALSE(d.time_reset);
  EXPECT_NEAR(d.held_stamp_s, kT0 + 300.0 + StampFilter::kTimeResetGapS, 1e-6);
  EXPECT_NEAR(d.stamp_s, kT0 + 300.02 + StampFilter::kTimeResetGapS, 1e-6);
  EXPECT_EQ(filter.time_resets(), 1);
}

// One stale odometry stamp 10 s back is no loop: the next message is back on the old clock,
// so it alone is dropped and the time base stays.
TEST(StampFilterTest, OneStaleOdometryStampIsNoTimeReset) {
  StampFilter filter = MakeFilter();
  int accepted = 0, dropped = 0;
  for (int i = 0; i < 1000; ++i) {
    const double stamp_s = kT0 + 0.02 * i - (i == 600 ? 10.0 : 0.0);
    const auto d = filter.Check(kOdometry, stamp_s);
    accepted += d.verdict == Verdict::kAccept;
    dropped += d.held == Held::kDrop;
    if (d.verdict == Verdict::kAccept) EXPECT_DOUBLE_EQ(d.stamp_s, stamp_s) << i;
  }
  EXPECT_EQ(accepted, 999);
  EXPECT_EQ(dropped, 1);
  EXPECT_EQ(filter.time_resets(), 0);
}

// One scan stamped 40 years back is not a loop: held, then dropped when the next scan is on
// the old clock; confirmed, it is a time reset after all.
TEST(StampFilterTest, HugeBackwardsJumpNeedsConfirmation) {
  StampFilter filter = MakeFilter();
  EXPECT_EQ(filter.Check(kLaser, kT0).verdict, Verdict::kAccept);
  EXPECT_EQ(filter.Check(kLaser, 1000.0).verdict, Verdict::kHold);
  auto d = filter.Check(kLaser, kT0 + 0.1);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_EQ(d.held, Held::kDrop);
  EXPECT_EQ(filter.time_resets(), 0);

  EXPECT_EQ(filter.Check(kLaser, 1000.0).verdict, Verdict::kHold);
  d = filter.Check(kLaser, 1000.1);
  EXPECT_EQ(d.held, Held::kRelease);
  EXPECT_TRUE(d.time_reset);
  EXPECT_NEAR(d.held_stamp_s, kT0 + 0.1 + StampFilter::kTimeResetGapS, 1e-6);
  EXPECT_NEAR(d.stamp_s, kT0 + 0.2 + StampFilter::kTimeResetGapS, 1e-6);
}

// Issue 18 item 10: after --resume, a replay from the log's start is skipped up to the
// checkpoint, not taken as a time reset; after that point a loop is a reset again.
TEST(StampFilterTest, ResumePointSkipsAlreadyMappedData) {
  StampFilter filter = MakeFilter();
  filter.SetResumePoint(kLaser, kT0 + 100.0);
  filter.SetResumePoint(kOdometry, kT0 + 100.01);
  EXPECT_EQ(filter.Check(kLaser, kT0).verdict, Verdict::kSkip);
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 100.01).verdict, Verdict::kSkip);
  EXPECT_EQ(filter.Check(kLaser, kT0 + 100.0).verdict, Verdict::kSkip);
  EXPECT_EQ(filter.Check(kLaser, kT0 + 100.1).verdict, Verdict::kAccept);
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 100.11).verdict, Verdict::kAccept);
  EXPECT_EQ(filter.time_resets(), 0);
  EXPECT_TRUE(filter.Check(kLaser, kT0).time_reset);
}

// An outlier in the replayed part must not end the skipping: the data after it up to the
// checkpoint is still already mapped, not "going backwards".
TEST(StampFilterTest, OutlierBeforeTheResumePointDoesNotEndTheSkipping) {
  StampFilter filter = MakeFilter();
  filter.SetResumePoint(kOdometry, kT0 + 100.0);
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 1.0).verdict, Verdict::kSkip);
  EXPECT_EQ(filter.Check(kOdometry, kT0 + 1e6).verdict, Verdict::kHold);
  for (int i = 2; i <= 100; ++i) {
    EXPECT_EQ(filter.Check(kOdometry, kT0 + i).verdict, Verdict::kSkip) << i;
  }
  const auto d = filter.Check(kOdometry, kT0 + 100.5);
  EXPECT_EQ(d.verdict, Verdict::kAccept);
  EXPECT_EQ(d.held, Held::kDrop);
}

TEST(StampFilterTest, OptionsValidated) {
  std::string error;
  EXPECT_TRUE(StampFilterOptions().IsValid(&error));
  StampFilterOptions options;
  options.max_jump_s = 0.0;
  EXPECT_FALSE(options.IsValid(&error));
  options = StampFilterOptions();
  options.max_time_reset_s = 1.0;
  EXPECT_FALSE(options.IsValid(&error));
}

}  // namespace
}  // namespace sensor
}  // namespace fusemap
