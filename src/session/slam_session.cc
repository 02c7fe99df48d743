#include "fusemap/session/slam_session.h"

#include <limits>
#include <utility>

namespace fusemap {
namespace session {
namespace {

// The pose graph's placements since the last call, as the cloud takes them.
std::vector<cloud::SubmapPose2d> TakePlacements(pose_graph::MapBuilder2D* builder) {
  std::vector<cloud::SubmapPose2d> placements;
  for (const pose_graph::SubmapPlacement& p : builder->pose_graph().TakeSubmapPlacements()) {
    placements.push_back({p.submap, p.T_map_submap});
  }
  return placements;
}

}  // namespace

SlamSession::SlamSession(const io::SlamConfig& config, common::Executor* executor,
                         bool record_cloud_cost)
    : config_(config),
      executor_(executor),
      builder_(std::make_unique<pose_graph::MapBuilder2D>(config_.map_builder, executor)) {
  if (config_.cloud.enabled) {
    cloud_stage_ = std::make_unique<CloudStage>(config_.cloud, record_cloud_cost);
  }
  MakeVisualStage();
}

void SlamSession::MakeVisualStage() {
  if (!config_.visual_loop.enabled) return;
  visual_stage_ = std::make_unique<VisualStage>(config_.visual_loop, config_.cloud,
                                                &builder_->pose_graph());
}

void SlamSession::Restore(const pose_graph::MapBuilderState2D& state,
                          std::vector<sensor::OdometryData> odometry) {
  builder_ = pose_graph::MapBuilder2D::Restore(config_.map_builder, executor_, state);
  odometry_ = std::move(odometry);
  // The stage holds the graph it applies its decisions to.
  MakeVisualStage();
}

double SlamSession::last_odometry_stamp_s() const {
  if (!odometry_.empty()) return odometry_.back().stamp_s;
  if (archive_) return archive_->mark().last_odometry_stamp_s;
  return -std::numeric_limits<double>::infinity();
}

std::optional<pose_graph::MapBuilder2D::ScanResult> SlamSession::AddScan(
    const sensor::LaserScan& scan) {
  auto result = builder_->AddScan(scan);
  if (!cloud_stage_ && !visual_stage_) return result;
  CloudPoseUpdate update;
  if (cloud_stage_) update.placements = TakePlacements(builder_.get());
  if (result && result->submap_id >= 0) {
    update.submap_id = result->submap_id;
    update.stamp_s = scan.stamp_s;
    update.T_local_tracking = result->T_local_tracking;
    update.T_local_submap = result->T_local_submap;
    update.node_id = result->node;
  }
  if (update.empty()) return result;
  if (visual_stage_) {
    if (visual_sink_.update) {
      visual_sink_.update(update);
    } else {
      visual_stage_->Apply(update);
    }
  }
  if (cloud_stage_) SendToCloud(std::move(update));
  return result;
}

bool SlamSession::AddOdometry(const sensor::OdometryData& odometry) {
  // The densified trajectory needs a time-ordered record.
  if (odometry.stamp_s < last_odometry_stamp_s()) return false;
  if (time_reset_pending_) odometry_breaks_s_.push_back(odometry.stamp_s);
  time_reset_pending_ = false;
  odometry_.push_back(odometry);
  builder_->AddOdometry(odometry);
  return true;
}

void SlamSession::AddImu(const sensor::ImuData& imu) { builder_->AddImu(imu); }

void SlamSession::AddRgbdFrame(const sensor::RgbdFrame& frame) {
  if (cloud_stage_ && !cloud_sink_) cloud_stage_->AddFrame(frame);
  if (visual_stage_ && !visual_sink_.update) visual_stage_->AddFrame(frame);
}

void SlamSession::SendToCloud(CloudPoseUpdate&& update) {
  if (cloud_sink_) {
    cloud_sink_(std::move(update));
  } else {
    cloud_stage_->Apply(update);
  }
}

void SlamSession::Finish() {
  if (visual_stage_) {
    // Laser loops still being searched are arbitrated too, before the final optimisation.
    executor_->WaitIdle();
    if (visual_sink_.finish) {
      visual_sink_.finish();
    } else {
      visual_stage_->Finish();
    }
  }
  builder_->Finish();
  if (!cloud_stage_) return;
  CloudPoseUpdate last;
  last.placements = TakePlacements(builder_.get());
  if (cloud_sink_) {
    cloud_sink_(std::move(last));
  } else {
    cloud_stage_->Finish(last);
  }
}

bool SlamSession::ArchiveSettled(std::string* error) {
  if (!archive_) return true;
  // Nodes leave the graph only once they are on disk: a failed append (a full disk) keeps
  // them, and the odometry, in memory for the next try.
  const auto nodes = builder_->pose_graph().TrimmedNodes();
  if (!archive_->Append(nodes, &odometry_, error)) return false;
  std::vector<int> indices;
  indices.reserve(nodes.size());
  for (const auto& node : nodes) indices.push_back(node.node);
  builder_->pose_graph().RemoveTrimmedNodes(indices);
  return true;
}

bool SlamSession::WriteOutputs(const std::string& dir, RunOutputsReport* report,
                               std::string* error) const {
  RunOutputs run;
  run.builder = builder_.get();
  run.odometry = &odometry_;
  run.odometry_breaks_s = odometry_breaks_s_;
  run.map_resolution_m = config_.map_builder.local_slam.submaps.resolution_m;
  run.cloud_mapper = cloud_stage_ ? &cloud_stage_->mapper() : nullptr;
  run.archive = archive_.get();
  run.loop_records = visual_stage_ ? &visual_stage_->records() : nullptr;
  return WriteRunOutputs(run, dir, report, error);
}

}  // namespace session
}  // namespace fusemap
