// Issue 16: a bad value in a profile is reported against its own key path and line, for every
// options struct a fusemapd profile reaches (the SLAM profile of io::ParseSlamConfig plus
// daemon:). Before, `local_slam.ceres_scan_matcher.max_num_iterations: 0` was reported as
// `local_slam.ceres_scan_matcher.ceres_scan_matcher` and `local_slam.voxel_filter_size_m`,
// without a line.
#include <gtest/gtest.h>

#include <string>

#include "fusemap/common/config_reader.h"
#include "fusemap/daemon/daemon_options.h"
#include "fusemap/io/slam_config.h"

namespace fusemap {
namespace daemon {
namespace {

// Parses a profile as LoadDaemonConfig does; returns Finish()'s error ("" when it passes).
std::string ProfileError(const std::string& yaml) {
  std::string error;
  auto reader = common::ConfigReader::FromString(yaml, "profile.yaml", &error);
  if (!reader) return "no reader: " + error;
  io::SlamConfig slam;
  io::ParseSlamConfig(*reader, &slam);
  ParseDaemonOptions(reader->Child("daemon"));
  return reader->Finish(&error) ? "" : error;
}

// A profile with one valid key first, then `key_path: value` written as nested mappings, so the
// bad value sits on line 2 + depth.
std::string ProfileSetting(const std::string& key_path, const std::string& value, int* line) {
  std::string yaml = "channels:\n  lidar: LIDAR\n";
  *line = 2;
  std::string indent;
  size_t begin = 0;
  for (size_t dot = key_path.find('.'); dot != std::string::npos;
       begin = dot + 1, dot = key_path.find('.', begin)) {
    yaml += indent + key_path.substr(begin, dot - begin) + ":\n";
    indent += "  ";
    ++*line;
  }
  yaml += indent + key_path.substr(begin) + ": " + value + "\n";
  ++*line;
  return yaml;
}

struct BadValue {
  const char* options_struct;  // whose check rejects the value
  const char* key_path;
  const char* value;
};

// One bad value per options struct (and per place a struct is read from).
const BadValue kBadValues[] = {
    {"io::LidarChannelConfig", "lidar.range_min_m", "-1"},
    {"mapping::LocalTrajectoryBuilderOptions2D", "local_slam.voxel_filter_size_m", "0"},
    {"mapping::LocalTrajectoryBuilderOptions2D", "local_slam.T_tracking_laser", "[1, 2]"},
    {"sensor::RangeGateOptions", "local_slam.range_gate.missing_data_ray_length_m", "0"},
    {"sensor::AdaptiveVoxelFilterOptions", "local_slam.adaptive_voxel_filter.min_num_points", "0"},
    {"sensor::AdaptiveVoxelFilterOptions",
     "local_slam.loop_closure_adaptive_voxel_filter.max_length_m", "0"},
    {"mapping::InitialMatchOptions2D", "local_slam.initial_branch_and_bound_match.min_score_gain",
     "2"},
    {"mapping::FastCorrelativeScanMatcherOptions2D (inline)",
     "local_slam.initial_branch_and_bound_match.branch_and_bound_depth", "0"},
    {"mapping::RealTimeCorrelativeScanMatcherOptions2D",
     "local_slam.real_time_correlative_scan_matcher.angular_search_window_rad", "4"},
    {"mapping::CeresScanMatcherOptions2D", "local_slam.ceres_scan_matcher.max_num_iterations", "0"},
    {"mapping::MotionFilterOptions", "local_slam.motion_filter.max_distance_m", "-1"},
    {"mapping::SubmapsOptions", "local_slam.submaps.num_range_data", "0"},
    {"mapping::ProbabilityGridRangeDataInserterOptions",
     "local_slam.submaps.range_data_inserter.miss_probability", "0.7"},
    {"pose_graph::PoseGraphOptions2D", "global_slam.final_optimization_iterations", "0"},
    {"pose_graph::PoseGraphOptions2D", "global_slam.matcher_memory_budget_mb", "0"},
    {"pose_graph::PoseGraphOptions2D", "global_slam.max_pending_searches", "0"},
    {"pose_graph::ConstraintBuilderOptions2D", "global_slam.constraint_builder.sampling_ratio",
     "1.5"},
    {"mapping::FastCorrelativeScanMatcherOptions2D",
     "global_slam.constraint_builder.fast_correlative_scan_matcher.min_score", "1.5"},
    {"mapping::CeresScanMatcherOptions2D",
     "global_slam.constraint_builder.ceres_scan_matcher.num_threads", "0"},
    {"pose_graph::OptimizationOptions", "global_slam.optimization.linear_solver", "qr"},
    {"pose_graph::OverlappingSubmapsTrimmerOptions2D",
     "global_slam.overlapping_submaps_trimmer.min_added_submaps_count", "0"},
    {"pose_graph::LoopClosureVerificationOptions2D",
     "global_slam.loop_closure_verification.max_node_gap", "0"},
    {"cloud::CloudMapperOptions", "cloud.max_pending_frames", "0"},
    {"cloud::CloudMapperOptions", "cloud.T_base_camera_rpy_deg", "[0, 90]"},
    {"cloud::FrameCloudOptions", "cloud.frame.pixel_stride", "0"},
    {"cloud::PoseInterpolatorOptions", "cloud.sync.max_gap_s", "0"},
    {"cloud::CloudBinderOptions", "cloud.binder.index_block_voxels", "65"},
    {"cloud::FreeColumnFilterOptions", "cloud.laser_free_space.margin_m", "3"},
    {"daemon::DaemonOptions", "daemon.sensor_queue_size", "0"},
    {"daemon::DaemonOptions", "daemon.health_channel", "''"},
    {"sensor::StampFilterOptions (in daemon:)", "daemon.max_stamp_jump_s", "0"},
    {"sensor::StampFilterOptions (in daemon:)", "daemon.max_time_reset_s", "1"},
};

TEST(ConfigErrorsTest, EachBadValueIsReportedOnceAgainstItsKeyPathAndLine) {
  for (const BadValue& bad : kBadValues) {
    int line = 0;
    const std::string yaml = ProfileSetting(bad.key_path, bad.value, &line);
    const std::string error = ProfileError(yaml);
    const std::string expected =
        "profile.yaml:" + std::to_string(line) + ": key '" + bad.key_path + "': ";
    EXPECT_EQ(error.rfind(expected, 0), 0u)
        << bad.options_struct << "\n" << yaml << "expected: " << expected << "\ngot: " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos)
        << bad.options_struct << ": one problem, one line\n" << error;
  }
}

TEST(ConfigErrorsTest, TheValidSettingsAboveAreAccepted) {
  int line = 0;
  EXPECT_EQ(ProfileError(ProfileSetting("local_slam.ceres_scan_matcher.max_num_iterations", "1",
                                        &line)),
            "");
  EXPECT_EQ(ProfileError(ProfileSetting("daemon.max_stamp_jump_s", "1", &line)), "");
}

TEST(ConfigErrorsTest, EveryBadValueInAFileIsReported) {
  const std::string error = ProfileError(
      "local_slam:\n"
      "  voxel_filter_size_m: 0\n"
      "  ceres_scan_matcher:\n"
      "    max_num_iterations: 0\n"
      "    num_threads: 0\n"
      "daemon:\n"
      "  rgbd_queue_size: 0\n");
  EXPECT_NE(error.find("profile.yaml:2: key 'local_slam.voxel_filter_size_m': must be > 0"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("profile.yaml:4: key 'local_slam.ceres_scan_matcher.max_num_iterations': "
                       "must be >= 1"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("profile.yaml:5: key 'local_slam.ceres_scan_matcher.num_threads'"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("profile.yaml:7: key 'daemon.rgbd_queue_size'"), std::string::npos)
      << error;
}

// Options built in C++ (tests, defaults) get the field's path from IsValid().
TEST(ConfigErrorsTest, IsValidNamesTheFieldPath) {
  io::SlamConfig slam;
  slam.map_builder.local_slam.ceres_scan_matcher.max_num_iterations = 0;
  std::string error;
  EXPECT_FALSE(slam.map_builder.IsValid(&error));
  EXPECT_EQ(error, "local_slam.ceres_scan_matcher.max_num_iterations must be >= 1");

  DaemonOptions daemon;
  daemon.max_stamp_jump_s = 0.0;
  EXPECT_FALSE(daemon.IsValid(&error));
  EXPECT_EQ(error, "max_stamp_jump_s must be > 0");
  EXPECT_TRUE(DaemonOptions().IsValid(nullptr));
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
