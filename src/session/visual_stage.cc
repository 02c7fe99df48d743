#include "fusemap/session/visual_stage.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include <opencv2/imgproc.hpp>

#include "fusemap/cloud/frame_cloud.h"

namespace fusemap {
namespace session {
namespace {

// MotionLinkOptions::translation_weight is that of a link whose standard error is this.
constexpr double kMotionLinkReferenceSigmaM = 0.001;

pose_graph::Constraint2D::Source ToGraphSource(visual_loop::LoopSource source) {
  switch (source) {
    case visual_loop::LoopSource::kLaser:
      return pose_graph::Constraint2D::kLaser;
    case visual_loop::LoopSource::kVisual:
      return pose_graph::Constraint2D::kVisual;
    case visual_loop::LoopSource::kBoth:
      break;
  }
  return pose_graph::Constraint2D::kBoth;
}

// The laser side of an arbitration, from a loop constraint in the graph or a reported closure
// (pose_graph::Constraint2D, pose_graph::LoopClosure2D: the same fields).
template <typename LaserLoop>
visual_loop::LoopMeasurement2D LaserMeasurement(const LaserLoop& loop) {
  visual_loop::LoopMeasurement2D measurement;
  measurement.T_submap_node = loop.T_submap_node;
  measurement.laser_score = loop.laser_score;
  measurement.unmeasured_direction = loop.unmeasured_direction;
  measurement.unmeasured_turn_rad_per_m = loop.unmeasured_turn_rad_per_m;
  return measurement;
}

}  // namespace

visual_loop::CameraFrame ToCameraFrame(const sensor::RgbdFrame& frame,
                                       const cloud::CloudMapperOptions& camera,
                                       const visual_loop::KeyframeOptions& depth_range) {
  visual_loop::CameraFrame out;
  out.stamp_s = frame.stamp_s;
  const sensor::PinholeIntrinsics& k = frame.color_intrinsics;
  if (k.width <= 0 || k.height <= 0 || !(k.fx > 0.0) || !(k.fy > 0.0) ||
      frame.color_rgb.size() < 3 * static_cast<size_t>(k.width) * static_cast<size_t>(k.height)) {
    return out;
  }
  const cv::Mat rgb(k.height, k.width, CV_8UC3, const_cast<uint8_t*>(frame.color_rgb.data()));
  cv::cvtColor(rgb, out.image, cv::COLOR_RGB2GRAY);
  std::vector<float> depth_m =
      cloud::RegisterDepthImage(frame, depth_range.min_depth_m, depth_range.max_depth_m);
  if (!depth_m.empty()) out.depth_m = cv::Mat(k.height, k.width, CV_32FC1, depth_m.data()).clone();
  out.intrinsics = k;
  out.T_base_camera = cloud::CameraExtrinsic(camera, frame);
  return out;
}

std::string VisualSummaryLine(const VisualStageStats& s) {
  char line[640];
  std::snprintf(line, sizeof(line),
                "visual_loop: keyframes=%d candidates=%d verified=%d refused=%d "
                "laser_loops_checked=%d laser_confirmed=%d confirmed_along=%d visual_override=%d "
                "visual_forced=%d laser_kept=%d laser_rejected=%d visual_rejected=%d "
                "motion_links=%d motion_links_refused=%d motion_links_refined=%d frames_in=%lld "
                "frames_offered=%lld frames_dropped=%lld",
                s.checker.keyframes, s.checker.candidates, s.checker.verified, s.checker.rejected,
                s.laser_loops_checked, s.confirmed, s.confirmed_along, s.overridden, s.forced,
                s.kept, s.rejected, s.visual_rejected, s.motion_links, s.motion_links_refused,
                s.motion_links_refined, static_cast<long long>(s.frames_in),
                static_cast<long long>(s.frames_offered),
                static_cast<long long>(s.frames_dropped_no_pose + s.frames_dropped_pending));
  return line;
}

VisualStage::VisualStage(const io::VisualLoopConfig& config,
                         const cloud::CloudMapperOptions& camera, pose_graph::PoseGraph2D* graph)
    : config_(config),
      camera_(camera),
      graph_(graph),
      checker_(config.checker, config.loaded_vocabulary),
      interpolator_(camera.sync) {
  assert(config_.loaded_vocabulary != nullptr);
  graph_->ReportLoopClosures();
}

void VisualStage::Apply(const CloudPoseUpdate& update) {
  if (update.submap_id < 0) return;
  if (!interpolator_.AddPose(update.stamp_s, update.T_local_tracking)) return;
  // A scan that was not inserted keeps the node before it; the node's own pose is that of the
  // scan that made it.
  const bool same_node = !bindings_.empty() && bindings_.back().node == update.node_id;
  bindings_.push_back({update.stamp_s, update.node_id, update.submap_id,
                       same_node ? bindings_.back().T_local_node : update.T_local_tracking});
  while (bindings_.size() > 1 && bindings_[1].stamp_s < interpolator_.oldest_stamp_s()) {
    bindings_.pop_front();
  }
  newest_stamp_s_ = std::max(newest_stamp_s_, update.stamp_s);
  newest_node_ = std::max(newest_node_, update.node_id);
  ProcessPending();
  ProcessLaserLoops(false);
}

void VisualStage::AddFrame(const sensor::RgbdFrame& frame) {
  ++stats_.frames_in;
  // The checker never keeps frames closer than this; skip them before they cost a decode.
  if (frame.stamp_s - last_keyframe_stamp_s_ < config_.checker.selector.min_interval_s) return;
  if (static_cast<int>(pending_.size()) >= config_.max_pending_frames) {
    pending_.pop_front();
    ++stats_.frames_dropped_pending;
  }
  pending_.push_back(frame);
  ProcessPending();
}

void VisualStage::Finish() {
  finished_ = true;
  ProcessPending();
  ProcessLaserLoops(true);
}

void VisualStage::ProcessPending() {
  cloud::DrainPendingFrames(
      &pending_, &interpolator_, newest_stamp_s_, finished_, camera_.sync.hold_s,
      [](const sensor::RgbdFrame& frame) { return frame.stamp_s; },
      [this](const sensor::RgbdFrame& frame, const common::Rigid2d& T_local_base) {
        Offer(frame, T_local_base);
      },
      [this](const sensor::RgbdFrame&) { ++stats_.frames_dropped_no_pose; });
}

const VisualStage::Binding* VisualStage::BindingAt(double stamp_s) const {
  return cloud::LatestAtOrBefore(bindings_, stamp_s);
}

void VisualStage::Offer(const sensor::RgbdFrame& frame, const common::Rigid2d& T_local_base) {
  const Binding* binding = BindingAt(frame.stamp_s);
  if (binding == nullptr || binding->node < 0) {
    ++stats_.frames_dropped_no_pose;
    return;
  }
  if (frame.stamp_s - last_keyframe_stamp_s_ < config_.checker.selector.min_interval_s) return;
  const visual_loop::CameraFrame camera_frame =
      ToCameraFrame(frame, camera_, config_.checker.keyframe);
  if (camera_frame.image.empty()) {
    ++stats_.frames_unusable;
    return;
  }
  ++stats_.frames_offered;
  newest_offered_node_ = std::max(newest_offered_node_, binding->node);
  Pace();
  const visual_loop::VisualLoopChecker::FrameResult result =
      checker_.AddFrame(camera_frame, T_local_base, binding->node, binding->submap);
  if (!result.keyframe) return;
  last_keyframe_stamp_s_ = frame.stamp_s;
  keyframes_[result.keyframe_id] = {binding->node, binding->submap,
                                    binding->T_local_node.inverse() * T_local_base};
  if (config_.motion_links.enabled) LinkMotion(result.keyframe_id, T_local_base);
  last_keyframe_id_ = result.keyframe_id;
  T_local_last_keyframe_base_ = T_local_base;
  if (result.loop) HandleVisualLoop(*result.loop);
  ReleaseTrimmedSubmaps();
}

void VisualStage::LinkMotion(int id, const common::Rigid2d& T_local_base) {
  const auto previous = keyframes_.find(last_keyframe_id_);
  const auto current = keyframes_.find(id);
  // Keyframes of one node (the robot standing) measure no motion between nodes.
  if (previous == keyframes_.end() || current == keyframes_.end() ||
      previous->second.node >= current->second.node) {
    return;
  }
  const common::Rigid2d expected = T_local_last_keyframe_base_.inverse() * T_local_base;
  Pace();
  const visual_loop::VisualCheckResult result =
      checker_.CheckPlace(id, last_keyframe_id_, expected);
  if (result.check != visual_loop::VisualCheck::kVerified) {
    ++stats_.motion_links_refused;
    return;
  }
  // Local SLAM's motion over a keyframe spacing is good to centimetres; a camera measurement
  // far from it matched the wrong thing.
  const common::Rigid2d& measured = result.constraint->T_match_base_query_base;
  const common::Rigid2d difference = expected.inverse() * measured;
  if (difference.translation().norm() > config_.motion_links.max_disagreement_m ||
      std::abs(difference.angle_rad()) > config_.motion_links.max_disagreement_rad) {
    ++stats_.motion_links_refused;
    return;
  }
  pose_graph::NodeLink2D link;
  link.from = previous->second.node;
  link.to = current->second.node;
  link.T_from_to = previous->second.T_node_base * measured * current->second.T_node_base.inverse();
  // Weighted by the verifier's standard error of the translation: in the corridor world the
  // links whose stated error is in the worst quarter are 3x as far off as the best quarter.
  const Eigen::Matrix3d& covariance = result.constraint->covariance;
  const double sigma_m = std::sqrt(0.5 * (covariance(0, 0) + covariance(1, 1)));
  link.translation_weight = config_.motion_links.translation_weight * kMotionLinkReferenceSigmaM /
                            std::max(sigma_m, 1e-4);
  link.rotation_weight = config_.motion_links.rotation_weight;
  if (graph_->AddNodeLink(link)) {
    ++stats_.motion_links;
    stats_.motion_links_refined += result.refined_on_pixels;
  } else {
    ++stats_.motion_links_refused;
  }
}

std::optional<common::Rigid2d> VisualStage::T_submap_base(int submap, int id) const {
  const auto it = keyframes_.find(id);
  if (it == keyframes_.end()) return std::nullopt;
  const std::optional<common::Rigid2d> T_submap_node = graph_->T_submap_node(submap, it->second.node);
  if (!T_submap_node) return std::nullopt;
  return *T_submap_node * it->second.T_node_base;
}

double VisualStage::PathLengthM(int node_a, int node_b) const {
  const std::shared_ptr<const pose_graph::PoseGraphSnapshot> snapshot = graph_->Snapshot();
  const int from = std::min(node_a, node_b);
  const int to = std::max(node_a, node_b);
  double path_m = 0.0;
  const common::Rigid2d* previous = nullptr;
  // node_ids ascend.
  for (size_t i = 0; i < snapshot->node_ids.size(); ++i) {
    if (snapshot->node_ids[i] < from) continue;
    if (snapshot->node_ids[i] > to) break;
    const common::Rigid2d& pose = snapshot->T_map_nodes[i];
    if (previous != nullptr) path_m += (pose.translation() - previous->translation()).norm();
    previous = &pose;
  }
  return path_m;
}

std::optional<visual_loop::LoopMeasurement2D> VisualStage::ForNode(
    const visual_loop::LoopMeasurement2D& base_measurement, int id, int submap, int node) const {
  // The keyframe's base relative to `node` by the current estimate: they are at most a few
  // nodes apart, over which the estimate is local SLAM's own motion.
  const std::optional<common::Rigid2d> T_submap_base_estimate = T_submap_base(submap, id);
  const std::optional<common::Rigid2d> T_submap_node = graph_->T_submap_node(submap, node);
  if (!T_submap_base_estimate || !T_submap_node) return std::nullopt;
  const common::Rigid2d T_node_base = T_submap_node->inverse() * *T_submap_base_estimate;
  visual_loop::LoopMeasurement2D measurement = base_measurement;
  measurement.T_submap_node = base_measurement.T_submap_node * T_node_base.inverse();
  return measurement;
}

void VisualStage::HandleVisualLoop(const visual_loop::VisualLoopConstraint& loop) {
  const int submap = loop.match_submap;
  const std::optional<common::Rigid2d> T_submap_match_base =
      T_submap_base(submap, loop.match_keyframe);
  const auto query = keyframes_.find(loop.query_keyframe);
  if (!T_submap_match_base || query == keyframes_.end()) return;
  const visual_loop::LoopMeasurement2D base_measurement =
      visual_loop::ToSubmapMeasurement(*T_submap_match_base, loop);
  // A laser loop of the same pair (the nearest node within max_node_gap) is arbitrated against
  // this one; without one the visual loop is forced.
  const int query_node = query->second.node;
  std::optional<pose_graph::Constraint2D> laser;
  for (const pose_graph::Constraint2D& c : graph_->LoopConstraints()) {
    if (c.submap != submap || c.source != pose_graph::Constraint2D::kLaser ||
        c.tag != pose_graph::Constraint2D::kInterSubmap ||
        std::abs(c.node - query_node) > config_.max_node_gap) {
      continue;
    }
    if (!laser || std::abs(c.node - query_node) < std::abs(laser->node - query_node)) laser = c;
  }
  const int node = laser ? laser->node : query_node;
  std::optional<visual_loop::LoopMeasurement2D> visual =
      ForNode(base_measurement, loop.query_keyframe, submap, node);
  if (!visual) return;
  const std::optional<common::Rigid2d> T_submap_node = graph_->T_submap_node(submap, node);
  std::optional<visual_loop::LoopMeasurement2D> laser_measurement;
  if (laser) {
    laser_measurement = LaserMeasurement(*laser);
    // Where the laser puts the query keyframe's base relative to the match keyframe's.
    const std::optional<common::Rigid2d> T_submap_query_base =
        T_submap_base(submap, loop.query_keyframe);
    // Counted only where the two disagree (a descriptor matching, ~1 ms): only there does the
    // arbiter weigh them.
    if (T_submap_query_base && T_submap_node &&
        visual_loop::LaserAndVisualDisagree(*laser_measurement, *visual, config_.arbitration)) {
      const common::Rigid2d T_match_query_laser = T_submap_match_base->inverse() *
                                                  laser->T_submap_node * T_submap_node->inverse() *
                                                  *T_submap_query_base;
      visual->visual_matches_explained_by_laser =
          checker_.MatchesExplained(loop.match_keyframe, loop.query_keyframe, T_match_query_laser);
    }
    const int id = laser->loop_id;
    laser_loops_.erase(std::remove_if(laser_loops_.begin(), laser_loops_.end(),
                                      [id](const pose_graph::LoopClosure2D& l) { return l.id == id; }),
                       laser_loops_.end());
  }
  // Without a laser loop, the correction it asks of the graph must be one drift explains.
  std::optional<visual_loop::GraphEstimate2D> estimate;
  const auto match = keyframes_.find(loop.match_keyframe);
  if (!laser && T_submap_node && match != keyframes_.end()) {
    estimate = visual_loop::GraphEstimate2D{*T_submap_node, PathLengthM(match->second.node, node)};
  }
  Apply(visual_loop::ArbitrateLoop(node, submap, laser_measurement, visual,
                                   visual_loop::VisualCheck::kVerified, config_.arbitration,
                                   estimate),
        laser ? laser->loop_id : -1);
}

void VisualStage::ProcessLaserLoops(bool all) {
  for (const pose_graph::LoopClosure2D& loop : graph_->TakeNewLoopClosures()) {
    laser_loops_.push_back(loop);
  }
  // A loop's place has been seen once frames past its node were offered; without frames (no
  // camera, or the camera lags) it is judged after 2 * max_node_gap more nodes.
  std::vector<pose_graph::LoopClosure2D> ready;
  for (auto it = laser_loops_.begin(); it != laser_loops_.end();) {
    if (all || it->node < newest_offered_node_ ||
        it->node + 2 * config_.max_node_gap < newest_node_) {
      ready.push_back(*it);
      it = laser_loops_.erase(it);
    } else {
      ++it;
    }
  }
  for (const pose_graph::LoopClosure2D& loop : ready) CheckLaserLoop(loop);
}

void VisualStage::CheckLaserLoop(const pose_graph::LoopClosure2D& loop) {
  const visual_loop::LoopMeasurement2D laser = LaserMeasurement(loop);
  std::optional<visual_loop::LoopMeasurement2D> visual;
  visual_loop::VisualCheck check = visual_loop::VisualCheck::kNotChecked;
  std::string check_reason;
  const int query = checker_.KeyframeNearestNode(loop.node);
  const auto query_info = keyframes_.find(query);
  const std::optional<common::Rigid2d> T_submap_node_estimate =
      graph_->T_submap_node(loop.submap, loop.node);
  const std::optional<common::Rigid2d> T_submap_query_estimate = T_submap_base(loop.submap, query);
  if (query_info != keyframes_.end() && T_submap_node_estimate && T_submap_query_estimate &&
      std::abs(query_info->second.node - loop.node) <= config_.max_node_gap) {
    // Where the laser says the query keyframe's base stands in the submap.
    const common::Rigid2d T_submap_query_laser =
        loop.T_submap_node * T_submap_node_estimate->inverse() * *T_submap_query_estimate;
    // The submap's keyframes nearest that place (a radian of turn counted as half a metre),
    // within the check gate; up to max_check_views of them, nearest first. One view that
    // verifies is the camera's answer; the loop counts as contradicted only if every view
    // tried contradicts it (one unlucky pair must not remove a laser loop).
    struct View {
      double cost;
      int id;
      common::Rigid2d expected;
    };
    std::vector<View> views;
    // A keyframe is bound to the older of the two submaps its node went into, so the first part
    // of a submap was seen by keyframes bound to the one before (their nodes are in both).
    std::vector<int> ids = checker_.KeyframesOfSubmap(loop.submap);
    if (loop.submap > 0) {
      const std::vector<int> previous = checker_.KeyframesOfSubmap(loop.submap - 1);
      ids.insert(ids.end(), previous.begin(), previous.end());
    }
    for (int id : ids) {
      if (id == query) continue;
      const std::optional<common::Rigid2d> T_submap_match = T_submap_base(loop.submap, id);
      if (!T_submap_match) continue;
      const common::Rigid2d T_match_query = T_submap_match->inverse() * T_submap_query_laser;
      if (T_match_query.translation().norm() > config_.max_check_distance_m ||
          std::abs(T_match_query.angle_rad()) > config_.max_check_yaw_rad) {
        continue;
      }
      views.push_back({T_match_query.translation().norm() + 0.5 * std::abs(T_match_query.angle_rad()),
                       id, T_match_query});
    }
    std::sort(views.begin(), views.end(),
              [](const View& a, const View& b) { return a.cost < b.cost; });
    if (static_cast<int>(views.size()) > config_.max_check_views) views.resize(config_.max_check_views);
    int contradicted = 0;
    for (const View& view : views) {
      Pace();
      const visual_loop::VisualCheckResult result = checker_.CheckPlace(query, view.id, view.expected);
      check_reason = result.reason;
      if (result.check == visual_loop::VisualCheck::kVerified) {
        visual = ForNode(visual_loop::ToSubmapMeasurement(*T_submap_base(loop.submap, view.id),
                                                          *result.constraint),
                         query, loop.submap, loop.node);
        if (visual) {
          if (visual_loop::LaserAndVisualDisagree(laser, *visual, config_.arbitration)) {
            visual->visual_matches_explained_by_laser =
                checker_.MatchesExplained(view.id, query, view.expected);
          }
          break;
        }
      }
      contradicted += result.check == visual_loop::VisualCheck::kContradicted;
    }
    if (visual) {
      check = visual_loop::VisualCheck::kVerified;
    } else if (contradicted > 0 && contradicted == static_cast<int>(views.size())) {
      check = visual_loop::VisualCheck::kContradicted;
    }
  }
  ++stats_.laser_loops_checked;
  visual_loop::ArbitrationRecord record =
      visual_loop::ArbitrateLoop(loop.node, loop.submap, laser, visual, check, config_.arbitration);
  // What the camera found, for loops.tsv.
  if (!check_reason.empty()) record.reason += " (" + check_reason + ")";
  Apply(record, loop.id);
}

void VisualStage::Apply(const visual_loop::ArbitrationRecord& record, int laser_id) {
  pose_graph::ExternalLoopConstraint2D constraint;
  constraint.node = record.node;
  constraint.submap = record.submap;
  if (record.chosen) constraint.T_submap_node = record.chosen->T_submap_node;
  constraint.translation_weight = config_.translation_weight;
  constraint.rotation_weight = config_.rotation_weight;
  constraint.source = ToGraphSource(record.source);
  switch (record.decision) {
    case visual_loop::LoopDecision::kLaserConfirmed:
      if (!graph_->SetLoopConstraintSource(laser_id, pose_graph::Constraint2D::kBoth)) return;
      ++stats_.confirmed;
      // A laser loop held across a corridor only measured nothing along it (nor, round a
      // curved one, the turn that goes with that): the camera's measurement of the same place
      // joins it at the camera's weights, so the revisit says where along the corridor it is.
      if (record.laser && record.visual && !record.laser->unmeasured_direction.isZero()) {
        pose_graph::ExternalLoopConstraint2D along = constraint;
        along.T_submap_node = record.visual->T_submap_node;
        along.source = pose_graph::Constraint2D::kVisual;
        if (graph_->AddLoopConstraint(along) >= 0) ++stats_.confirmed_along;
      }
      break;
    case visual_loop::LoopDecision::kVisualOverride:
      constraint.source = pose_graph::Constraint2D::kVisual;
      if (!graph_->ReplaceLoopConstraint(laser_id, constraint)) return;
      ++stats_.overridden;
      break;
    case visual_loop::LoopDecision::kVisualForced:
      // Refused for a node already in that submap (local SLAM ties them) or a trimmed one.
      if (graph_->AddLoopConstraint(constraint) < 0) return;
      ++stats_.forced;
      break;
    case visual_loop::LoopDecision::kLaserKept:
      ++stats_.kept;
      break;
    case visual_loop::LoopDecision::kLaserRejected:
      if (!graph_->RemoveLoopConstraint(laser_id)) return;
      ++stats_.rejected;
      break;
    case visual_loop::LoopDecision::kVisualRejected:
      ++stats_.visual_rejected;
      break;
  }
  records_.push_back(record);
}

void VisualStage::ReleaseTrimmedSubmaps() {
  std::set<int> submaps;
  for (const auto& entry : keyframes_) submaps.insert(entry.second.submap);
  const auto graph_submaps = graph_->submaps();
  for (int s : submaps) {
    if (s < 0 || s >= static_cast<int>(graph_submaps.size()) || graph_submaps[s]) continue;
    checker_.RemoveSubmap(s);
    for (auto it = keyframes_.begin(); it != keyframes_.end();) {
      it = it->second.submap == s ? keyframes_.erase(it) : std::next(it);
    }
  }
}

io::VisualKeyframesState VisualStage::ExportState() const {
  io::VisualKeyframesState state;
  state.next_keyframe_id = checker_.next_keyframe_id();
  for (visual_loop::SavedKeyframe& saved : checker_.ExportKeyframes()) {
    const common::Rigid2d T_node_base = keyframes_.at(saved.keyframe.id).T_node_base;
    state.keyframes.push_back({std::move(saved), T_node_base});
  }
  return state;
}

void VisualStage::RestoreState(io::VisualKeyframesState state) {
  std::vector<visual_loop::SavedKeyframe> saved;
  for (io::VisualKeyframesState::Entry& entry : state.keyframes) {
    const visual_loop::Keyframe& k = entry.saved.keyframe;
    keyframes_[k.id] = {k.node, k.submap, entry.T_node_base};
    saved.push_back(std::move(entry.saved));
  }
  checker_.RestoreKeyframes(std::move(saved), state.next_keyframe_id);
  // Keyframes of submaps trimmed since they were saved go at once.
  ReleaseTrimmedSubmaps();
}

VisualStageStats VisualStage::stats() const {
  VisualStageStats stats = stats_;
  stats.checker = checker_.stats();
  return stats;
}

}  // namespace session
}  // namespace fusemap
