#ifndef FUSEMAP_SESSION_SLAM_SESSION_H_
#define FUSEMAP_SESSION_SLAM_SESSION_H_

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fusemap/common/thread_pool.h"
#include "fusemap/io/slam_config.h"
#include "fusemap/io/trajectory_archive.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/sensor/sensor_types.h"
#include "fusemap/session/cloud_stage.h"
#include "fusemap/session/run_outputs.h"
#include "fusemap/session/visual_stage.h"

namespace fusemap {
namespace session {

// One mapping run, whoever drives it: fusemap_offline calls it in log order on one thread;
// fusemapd calls it from its SLAM thread and adds only threads, queues, LCM and checkpoints
// around it. It owns the map builder (local and global SLAM), the odometry record the
// trajectory is densified with, and the cloud stage, and writes the run's output files.
//
// Sensor messages come in stamped and in order (sensor::StampGate decides that before). The
// laser half (AddScan, AddOdometry, AddImu, Finish) hands the cloud half a CloudPoseUpdate
// after every scan: by default straight to the session's own CloudStage, on the caller's
// thread; with SetCloudSink, to whoever the sink gives it to (fusemapd's RGB-D thread), which
// then alone calls cloud_stage().
//
// With config.visual_loop.enabled the session also has a visual stage (the ORB visual loop
// checker, session::VisualStage) fed with the same pose updates and the RGB-D frames: inline
// by default (AddRgbdFrame, deterministic with an InlineExecutor); with SetVisualSink, the
// updates go to the sink and whoever owns the sink (fusemapd's visual thread) feeds
// visual_stage() the frames. Its forced and overriding constraints enter the final
// optimisation: Finish() waits for the stage to finish first.
class SlamSession {
 public:
  using CloudSink = std::function<void(CloudPoseUpdate&&)>;
  struct VisualSink {
    std::function<void(const CloudPoseUpdate&)> update;  // must not block
    std::function<void()> finish;  // returns once visual_stage()->Finish() has run
  };

  // `executor` runs loop-closure searches and optimisations; an InlineExecutor makes runs
  // bit-for-bit reproducible. With config.cloud.enabled the session has a cloud stage;
  // `record_cloud_cost` keeps its per-frame timings (CloudStage::cost).
  SlamSession(const io::SlamConfig& config, common::Executor* executor,
              bool record_cloud_cost = false);
  SlamSession(const SlamSession&) = delete;
  SlamSession& operator=(const SlamSession&) = delete;

  // Before any input: continue from a checkpointed state and the odometry record saved with it.
  void Restore(const pose_graph::MapBuilderState2D& state,
               std::vector<sensor::OdometryData> odometry);
  // Before any input: trimmed nodes and the odometry record move out of memory into `archive`
  // at each ArchiveSettled (fusemapd's checkpoints); the outputs read them back.
  void SetTrajectoryArchive(std::unique_ptr<io::TrajectoryArchive> archive) {
    archive_ = std::move(archive);
  }
  // Before any input: where cloud updates go instead of the session's own cloud stage.
  void SetCloudSink(CloudSink sink) { cloud_sink_ = std::move(sink); }
  // Before any input: where visual-stage updates go instead of the session's own stage.
  void SetVisualSink(VisualSink sink) { visual_sink_ = std::move(sink); }

  std::optional<pose_graph::MapBuilder2D::ScanResult> AddScan(const sensor::LaserScan& scan);
  // False (and nothing recorded) for odometry older than the record's newest sample.
  bool AddOdometry(const sensor::OdometryData& odometry);
  void AddImu(const sensor::ImuData& imu);
  // The input's time base was reset (sensor::StampFilter); before the first message on it.
  // Its stamp is recorded with the next odometry sample (odometry_breaks_s), so that the
  // densified trajectory takes no odometry increment across it; not kept across --resume.
  void OnTimeReset() {
    builder_->OnTimeReset();
    time_reset_pending_ = true;
  }
  // To the session's own cloud and visual stages; each ignored without one or with its sink.
  void AddRgbdFrame(const sensor::RgbdFrame& frame);
  // End of input: the visual stage's last decisions (after the executor's pending searches),
  // the final optimisation, and the cloud's last update (to the sink, which then finishes its
  // cloud stage with it; otherwise the session finishes its own).
  void Finish();

  // Moves the trimmed nodes and the odometry record into the archive (no-op without one).
  // The executor must be idle. On failure (a full disk) everything stays in memory.
  bool ArchiveSettled(std::string* error);
  // After Finish(): the run outputs (see session/run_outputs.h) into `dir`.
  bool WriteOutputs(const std::string& dir, RunOutputsReport* report, std::string* error) const;

  pose_graph::MapBuilder2D& builder() { return *builder_; }
  const pose_graph::MapBuilder2D& builder() const { return *builder_; }
  // The odometry accepted since the last ArchiveSettled (all of it without an archive).
  const std::vector<sensor::OdometryData>& odometry() const { return odometry_; }
  const std::vector<double>& odometry_breaks_s() const { return odometry_breaks_s_; }
  const io::TrajectoryArchive* archive() const { return archive_.get(); }
  // The newest odometry stamp recorded or archived; -inf before any.
  double last_odometry_stamp_s() const;
  // Null without config.cloud.enabled.
  CloudStage* cloud_stage() { return cloud_stage_.get(); }
  const CloudStage* cloud_stage() const { return cloud_stage_.get(); }
  // Null without config.visual_loop.enabled.
  VisualStage* visual_stage() { return visual_stage_.get(); }
  const VisualStage* visual_stage() const { return visual_stage_.get(); }
  const io::SlamConfig& config() const { return config_; }

 private:
  void SendToCloud(CloudPoseUpdate&& update);
  void MakeVisualStage();

  const io::SlamConfig config_;
  common::Executor* const executor_;
  std::unique_ptr<pose_graph::MapBuilder2D> builder_;
  std::vector<sensor::OdometryData> odometry_;
  std::vector<double> odometry_breaks_s_;  // the first odometry stamp after each time reset
  bool time_reset_pending_ = false;
  std::unique_ptr<io::TrajectoryArchive> archive_;
  std::unique_ptr<CloudStage> cloud_stage_;
  CloudSink cloud_sink_;
  std::unique_ptr<VisualStage> visual_stage_;
  VisualSink visual_sink_;
};

}  // namespace session
}  // namespace fusemap

#endif  // FUSEMAP_SESSION_SLAM_SESSION_H_
