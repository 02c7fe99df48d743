#ifndef FUSEMAP_IO_LCM_OUTPUT_CONVERSIONS_H_
#define FUSEMAP_IO_LCM_OUTPUT_CONVERSIONS_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/io/health_report.h"
#include "fusemap/pose_graph/pose_graph_2d.h"
#include "fusemap/pose_graph/pose_graph_snapshot.h"

namespace fusemap {
namespace io {

// Encoders of what fusemapd and the simulator publish (the input messages are in
// lcm_conversions.h): the daemon and the tools only put these bytes on a channel. The decoders
// read recordings of that output back (tests, evaluation).

// What fusemap_lcm::pose_t (libbot2 bot_core.pose_t) carries. The frames of velocity,
// rotation rate and acceleration are the sender's (the simulator's ground truth: velocity in
// the world frame, rates and acceleration in the body frame, without gravity).
struct PoseMessage {
  double stamp_s = 0.0;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d rotation_rate_radps = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration_mps2 = Eigen::Vector3d::Zero();
};

std::vector<uint8_t> EncodePose(const PoseMessage& pose);
// fusemapd's pose output: a planar T_map_tracking with zero rates (quaternion w = cos(yaw/2),
// z = sin(yaw/2), x = y = +0).
std::vector<uint8_t> EncodePlanarPose(double stamp_s, const common::Rigid2d& T_map_tracking);
// Checks the fingerprint and the exact size; refuses non-finite fields.
bool DecodePose(const void* data, int size, PoseMessage* out, std::string* error);

// fusemap_lcm::submap_list_t: every submap's optimised T_map_submap and the solve count.
std::vector<uint8_t> EncodeSubmapList(double stamp_s,
                                      const pose_graph::PoseGraphSnapshot& snapshot);

// Checks the layout (counts within bounds, no trailing bytes) before decoding; refuses
// non-finite poses. Fills solve_count and T_map_submaps.
bool DecodeSubmapList(const void* data, int size, double* stamp_s,
                      pose_graph::PoseGraphSnapshot* out, std::string* error);

// The newest loop decision of the visual loop checker, as loop_closure_t carries it; the
// default is what a run without the checker sends.
struct LoopNote {
  std::string source = "laser";  // laser, visual, both
  std::string decision;          // visual_loop::ToString(LoopDecision), "" without the checker
};

// fusemap_lcm::loop_closure_t: new and total loop closures, optimisations, the latest node,
// the newest decision's source and decision.
std::vector<uint8_t> EncodeLoopClosure(double stamp_s, int new_loop_closures,
                                       const pose_graph::PoseGraph2D::Stats& stats,
                                       int latest_node, const LoopNote& note = LoopNote());

// fusemap_lcm::health_t (skipped and trimmed_* are not on the wire).
std::vector<uint8_t> EncodeHealth(double stamp_s, const HealthReport& report);

// Checks the layout before decoding; skipped and trimmed_* come back 0.
bool DecodeHealth(const void* data, int size, double* stamp_s, HealthReport* out,
                  std::string* error);

// One changed region of the coloured map, its points in the submap frame.
struct CloudRegionUpdate {
  double stamp_s = 0.0;
  int submap_id = -1;
  common::Rigid3d T_map_submap;
  size_t total_points = 0;  // in the region, before decimation
  cloud::ColorCloud::Ptr points_submap;
};

// fusemap_lcm::cloud_region_t; T_map_submap's rotation as (w, x, y, z).
std::vector<uint8_t> EncodeCloudRegion(const CloudRegionUpdate& update);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_LCM_OUTPUT_CONVERSIONS_H_
