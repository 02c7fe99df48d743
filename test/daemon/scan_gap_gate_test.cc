#include "fusemap/daemon/scan_gap_gate.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace fusemap {
namespace daemon {
namespace {

using Clock = ScanGapGate::Clock;
using std::chrono::milliseconds;

constexpr Clock::time_point kRun = Clock::time_point::min();

TEST(ScanGapGateTest, WorkRunsAtOnceUntilTheScanIntervalIsKnown) {
  ScanGapGate gate;
  const Clock::time_point t0 = Clock::now();
  EXPECT_EQ(gate.WaitUntil(t0), kRun);
  gate.ScanDone(t0);
  EXPECT_EQ(gate.WaitUntil(t0 + milliseconds(20)), kRun);
}

TEST(ScanGapGateTest, WorkStartsOnlyInTheFirstPartOfTheIntervalAfterAScan) {
  ScanGapGate::Options options;
  options.fraction = 0.4;
  options.stall_intervals = 3.0;
  ScanGapGate gate(options);
  const Clock::time_point t0 = Clock::now();
  gate.ScanDone(t0);
  gate.ScanDone(t0 + milliseconds(40));
  EXPECT_NEAR(gate.interval_s(), 0.040, 1e-9);
  const Clock::time_point last = t0 + milliseconds(40);
  EXPECT_EQ(gate.WaitUntil(last + milliseconds(1)), kRun);
  EXPECT_EQ(gate.WaitUntil(last + milliseconds(15)), kRun);
  // Past 40 % of the interval: wait for the next scan, at most until scans count as stopped.
  EXPECT_EQ(gate.WaitUntil(last + milliseconds(17)), last + milliseconds(120));
  EXPECT_EQ(gate.WaitUntil(last + milliseconds(39)), last + milliseconds(120));
  // No scan for three intervals: the work is not held back any longer.
  EXPECT_EQ(gate.WaitUntil(last + milliseconds(120)), kRun);
}

TEST(ScanGapGateTest, AStallIsNotTakenForTheInterval) {
  ScanGapGate::Options options;
  options.max_interval_s = 0.5;
  ScanGapGate gate(options);
  const Clock::time_point t0 = Clock::now();
  gate.ScanDone(t0);
  gate.ScanDone(t0 + milliseconds(40));
  gate.ScanDone(t0 + milliseconds(5040));  // the laser stopped for five seconds
  EXPECT_NEAR(gate.interval_s(), 0.040, 1e-9);
  gate.ScanDone(t0 + milliseconds(5120));  // then one interval of 80 ms
  EXPECT_NEAR(gate.interval_s(), 0.95 * 0.040 + 0.05 * 0.080, 1e-9);
}

TEST(ScanGapGateTest, ClosedGateNeverHoldsWork) {
  ScanGapGate gate;
  const Clock::time_point t0 = Clock::now();
  gate.ScanDone(t0 - milliseconds(40));
  gate.ScanDone(t0);
  ASSERT_NE(gate.WaitUntil(t0 + milliseconds(30)), kRun);
  gate.Close();
  EXPECT_EQ(gate.WaitUntil(t0 + milliseconds(30)), kRun);
  gate.WaitForGap();  // returns
}

// Scans 10 s apart, the last 10 s ago: a worker must wait (up to 20 s more) for the next.
ScanGapGate::Options TenSecondScans() {
  ScanGapGate::Options options;
  options.max_interval_s = 100.0;
  return options;
}
void MarkTwoScansTenSecondsApart(ScanGapGate* gate) {
  const Clock::time_point t0 = Clock::now();
  gate->ScanDone(t0 - std::chrono::seconds(20));
  gate->ScanDone(t0 - std::chrono::seconds(10));
}

TEST(ScanGapGateTest, AScanReleasesAWaitingWorker) {
  ScanGapGate gate(TenSecondScans());
  MarkTwoScansTenSecondsApart(&gate);
  ASSERT_NE(gate.WaitUntil(Clock::now()), kRun);
  std::thread worker([&gate] { gate.WaitForGap(); });
  gate.ScanDone(Clock::now());  // the worker may start now: it returns long before the stall
  worker.join();
  EXPECT_EQ(gate.WaitUntil(Clock::now()), kRun);
}

TEST(ScanGapGateTest, ClosingReleasesAWaitingWorker) {
  ScanGapGate gate(TenSecondScans());
  MarkTwoScansTenSecondsApart(&gate);
  ASSERT_NE(gate.WaitUntil(Clock::now()), kRun);
  std::thread worker([&gate] { gate.WaitForGap(); });
  gate.Close();
  worker.join();
  EXPECT_EQ(gate.WaitUntil(Clock::now()), kRun);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
