#include "fusemap/sensor/stamp_gate.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fusemap {
namespace sensor {
namespace {

constexpr int kLaser = 0, kOdometry = 1;
constexpr double kT0 = 1700000000.0;

struct Message {
  double stamp_s = 0.0;
  int id = 0;
};

// What a consumer of the gate receives, in order.
class Sink {
 public:
  explicit Sink(StampGate<Message>* gate) : gate_(gate) {}
  void Offer(int channel, double stamp_s, int id) {
    Message message{stamp_s, id};
    auto result = gate_->Offer(channel, message);
    if (result.released) received.push_back(*result.released);
    if (result.pass) received.push_back(message);
  }
  std::vector<Message> received;

 private:
  StampGate<Message>* gate_;
};

StampGate<Message> MakeGate() {
  return StampGate<Message>(StampFilterOptions(), 2, kLaser,
                            [](Message& m) -> double& { return m.stamp_s; });
}

// Issue 18 item 6: one outlier stamp costs that message alone; the rest pass in order.
TEST(StampGateTest, OutlierIsHeldThenDroppedAlone) {
  StampGate<Message> gate = MakeGate();
  Sink sink(&gate);
  for (int i = 0; i < 100; ++i) {
    sink.Offer(kOdometry, kT0 + 0.02 * i + (i == 10 ? 11.6 * 86400.0 : 0.0), i);
  }
  ASSERT_EQ(sink.received.size(), 99u);
  for (size_t k = 0; k < sink.received.size(); ++k) {
    EXPECT_NE(sink.received[k].id, 10);
    if (k > 0) EXPECT_GT(sink.received[k].stamp_s, sink.received[k - 1].stamp_s);
  }
  EXPECT_EQ(gate.num_held(), 0);
}

// A jump the next message confirms: the held message goes on first, then the new one.
TEST(StampGateTest, ConfirmedJumpReleasesTheHeldMessageFirst) {
  StampGate<Message> gate = MakeGate();
  Sink sink(&gate);
  sink.Offer(kLaser, kT0, 0);
  sink.Offer(kLaser, kT0 + 1000.0, 1);  // held
  EXPECT_EQ(gate.num_held(), 1);
  ASSERT_EQ(sink.received.size(), 1u);
  sink.Offer(kLaser, kT0 + 1000.1, 2);  // confirms it
  ASSERT_EQ(sink.received.size(), 3u);
  EXPECT_EQ(sink.received[1].id, 1);
  EXPECT_EQ(sink.received[2].id, 2);
  EXPECT_DOUBLE_EQ(sink.received[1].stamp_s, kT0 + 1000.0);
  EXPECT_EQ(gate.num_held(), 0);
}

// A held message nothing confirmed is still held at the end: the caller counts it as lost.
TEST(StampGateTest, UnconfirmedJumpAtTheEndStaysHeld) {
  StampGate<Message> gate = MakeGate();
  Sink sink(&gate);
  sink.Offer(kLaser, kT0, 0);
  sink.Offer(kOdometry, kT0 + 5000.0, 1);
  EXPECT_EQ(sink.received.size(), 1u);
  EXPECT_EQ(gate.num_held(), 1);
}

}  // namespace
}  // namespace sensor
}  // namespace fusemap
