#ifndef FUSEMAP_TEST_TESTING_NULL_PUBLISHER_H_
#define FUSEMAP_TEST_TESTING_NULL_PUBLISHER_H_

#include "fusemap/daemon/publisher.h"

namespace fusemap {
namespace test_world {

// A daemon publisher that drops everything, for engine tests that only look at the result.
class NullPublisher : public daemon::Publisher {
 public:
  void PublishPose(double, const common::Rigid2d&) override {}
  void PublishSubmapList(double, const pose_graph::PoseGraphSnapshot&) override {}
  void PublishLoopClosure(double, int, const pose_graph::PoseGraph2D::Stats&, int,
                          const io::LoopNote&) override {}
  void PublishHealth(double, const daemon::HealthReport&) override {}
};

}  // namespace test_world
}  // namespace fusemap

#endif  // FUSEMAP_TEST_TESTING_NULL_PUBLISHER_H_
