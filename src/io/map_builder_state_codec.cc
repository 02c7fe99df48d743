#include "map_builder_state_codec.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "submap_state_codec.h"

namespace fusemap {
namespace io {
namespace {

void PutStats(const pose_graph::PoseGraph2D::Stats& s, ByteWriter* out) {
  for (int v : {s.nodes, s.submaps, s.finished_submaps, s.intra_constraints,
                s.loop_closure_searches, s.loop_closures_found, s.optimizations, s.trimmed_submaps,
                s.trimmed_nodes}) {
    out->I32(v);
  }
  for (double v : {s.loop_closure_search_s, s.precomputation_s, s.optimization_s, s.trimming_s}) {
    out->F64(v);
  }
}

bool GetStats(ByteReader* in, pose_graph::PoseGraph2D::Stats* s) {
  return in->I32(&s->nodes) && in->I32(&s->submaps) && in->I32(&s->finished_submaps) &&
         in->I32(&s->intra_constraints) && in->I32(&s->loop_closure_searches) &&
         in->I32(&s->loop_closures_found) && in->I32(&s->optimizations) &&
         in->I32(&s->trimmed_submaps) && in->I32(&s->trimmed_nodes) &&
         in->F64(&s->loop_closure_search_s) && in->F64(&s->precomputation_s) &&
         in->F64(&s->optimization_s) && in->F64(&s->trimming_s);
}

void PutLocal(const mapping::LocalTrajectoryBuilderState2D& local, ByteWriter* out) {
  const mapping::PoseExtrapolatorState2D& e = local.extrapolator;
  out->U64(e.poses.size());
  for (const auto& p : e.poses) {
    out->F64(p.stamp_s);
    EncodeRigid2d(p.pose, out);
  }
  out->U64(e.odometry.size());
  for (const auto& o : e.odometry) {
    out->F64(o.stamp_s);
    EncodeRigid2d(o.pose, out);
  }
  out->U64(e.imu.size());
  for (const auto& imu : e.imu) {
    out->F64(imu.stamp_s);
    for (int i = 0; i < 3; ++i) out->F64(imu.linear_acceleration_mps2[i]);
    for (int i = 0; i < 3; ++i) out->F64(imu.angular_velocity_radps[i]);
  }
  out->F64(e.linear_velocity_mps.x());
  out->F64(e.linear_velocity_mps.y());
  out->F64(e.angular_velocity_radps);
  out->F64(local.last_scan_stamp_s);
  out->F64(local.last_insertion_stamp_s);
  EncodeRigid2d(local.T_local_last_insertion, out);
  const auto& s = local.stats;
  for (int v : {s.scans, s.too_few_returns, s.out_of_order, s.inserted, s.odometry_rejected,
                s.imu_rejected}) {
    out->I32(v);
  }
  out->U64(local.heading_corrections_rad.size());
  for (const double c : local.heading_corrections_rad) out->F64(c);
}

bool GetLocal(ByteReader* in, mapping::LocalTrajectoryBuilderState2D* local) {
  mapping::PoseExtrapolatorState2D& e = local->extrapolator;
  size_t n = 0;
  if (!in->Count(32, &n)) return false;
  e.poses.resize(n);
  for (auto& p : e.poses) {
    if (!in->F64(&p.stamp_s) || !DecodeRigid2d(in, &p.pose)) return false;
  }
  if (!in->Count(32, &n)) return false;
  e.odometry.resize(n);
  for (auto& o : e.odometry) {
    if (!in->F64(&o.stamp_s) || !DecodeRigid2d(in, &o.pose)) return false;
  }
  if (!in->Count(56, &n)) return false;
  e.imu.resize(n);
  for (auto& imu : e.imu) {
    if (!in->F64(&imu.stamp_s)) return false;
    for (int i = 0; i < 3; ++i) {
      if (!in->F64(&imu.linear_acceleration_mps2[i])) return false;
    }
    for (int i = 0; i < 3; ++i) {
      if (!in->F64(&imu.angular_velocity_radps[i])) return false;
    }
  }
  auto& s = local->stats;
  if (!(in->F64(&e.linear_velocity_mps.x()) && in->F64(&e.linear_velocity_mps.y()) &&
        in->F64(&e.angular_velocity_radps) && in->F64(&local->last_scan_stamp_s) &&
        in->F64(&local->last_insertion_stamp_s) &&
        DecodeRigid2d(in, &local->T_local_last_insertion) && in->I32(&s.scans) &&
        in->I32(&s.too_few_returns) && in->I32(&s.out_of_order) && in->I32(&s.inserted) &&
        in->I32(&s.odometry_rejected) && in->I32(&s.imu_rejected))) {
    return false;
  }
  // The adaptive heading prior's window (format 7).
  if (!in->Count(8, &n)) return false;
  local->heading_corrections_rad.resize(n);
  for (double& c : local->heading_corrections_rad) {
    if (!in->F64(&c)) return false;
  }
  return true;
}

}  // namespace

void EncodeMapBuilderState(const pose_graph::MapBuilderState2D& state, bool compress_grids,
                           ByteWriter* out) {
  const pose_graph::PoseGraphState2D& g = state.pose_graph;
  out->U64(state.submaps.size());
  for (size_t s = 0; s < state.submaps.size(); ++s) {
    // Trimmed submaps have no grid to store.
    const bool has_grid = !g.submaps[s].trimmed;
    out->U8(has_grid ? 1 : 0);
    if (has_grid) EncodeSubmapState(state.submaps[s], compress_grids, out);
  }
  out->U64(g.nodes.size());
  for (const auto& node : g.nodes) {
    out->I32(node.index);
    out->F64(node.stamp_s);
    EncodeRigid2d(node.T_local_node, out);
    out->U64(node.cloud.size());
    for (const auto& p : node.cloud) {
      out->F32(p.x());
      out->F32(p.y());
    }
    out->U64(node.inserted_into.size());
    for (int s : node.inserted_into) out->I32(s);
    out->U8(node.trimmed ? 1 : 0);
    out->F64(node.path_m);
  }
  out->U64(g.submaps.size());
  for (const auto& s : g.submaps) {
    out->U8(s.finished ? 1 : 0);
    out->U8(s.trimmed ? 1 : 0);
    out->U8(s.matcher_ready ? 1 : 0);
    out->I64(s.sampler_pulses);
    out->F64(s.first_path_m);
    out->F64(s.last_path_m);
  }
  out->U64(g.T_map_nodes.size());
  for (const auto& T : g.T_map_nodes) EncodeRigid2d(T, out);
  out->U64(g.T_map_submaps.size());
  for (const auto& T : g.T_map_submaps) EncodeRigid2d(T, out);
  out->U64(g.constraints.size());
  for (const auto& c : g.constraints) {
    out->I32(c.submap);
    out->I32(c.node);
    EncodeRigid2d(c.T_submap_node, out);
    out->F64(c.translation_weight);
    out->F64(c.rotation_weight);
    // 0 intra-submap, 1 loop closure, 2 loop-closure candidate (older files hold only 0 and 1).
    out->U8(static_cast<uint8_t>(c.tag));
    // Format 4: what measured it (0 laser, 1 visual, 2 both), its loop id, the laser score.
    out->U8(static_cast<uint8_t>(c.source));
    out->I32(c.loop_id);
    out->F64(c.laser_score);
    // Format 5: the direction a laser loop closure does not measure (0, 0 when none).
    out->F64(c.unmeasured_direction.x());
    out->F64(c.unmeasured_direction.y());
    // Format 9: the turn that goes with it (a curved wall).
    out->F64(c.unmeasured_turn_rad_per_m);
  }
  out->U64(g.searches_in_flight.size());
  for (const auto& s : g.searches_in_flight) {
    out->I32(s.node);
    out->I32(s.submap);
    EncodeRigid2d(s.T_submap_node, out);
  }
  out->U8(g.optimization_pending ? 1 : 0);
  out->I32(g.nodes_since_optimization);
  out->I32(g.finished_submaps_at_last_trim);
  out->U64(g.solve_count);
  out->I32(g.next_loop_id);
  PutStats(g.stats, out);
  PutLocal(state.local_slam, out);
  out->U64(state.active_submaps.size());
  for (int s : state.active_submaps) out->I32(s);
  // Format 8: node links (the camera's motion between keyframes).
  out->U64(g.node_links.size());
  for (const auto& link : g.node_links) {
    out->I32(link.from);
    out->I32(link.to);
    EncodeRigid2d(link.T_from_to, out);
    out->F64(link.translation_weight);
    out->F64(link.rotation_weight);
  }
}

namespace {

bool InRange(int index, size_t size) { return index >= 0 && static_cast<size_t>(index) < size; }

// MapBuilderState2D's invariants, which MapBuilder2D::Restore asserts rather than checks.
bool CheckInvariants(const pose_graph::MapBuilderState2D& state, ByteReader* in) {
  const pose_graph::PoseGraphState2D& g = state.pose_graph;
  const size_t num_submaps = state.submaps.size();
  const size_t num_nodes = g.nodes.size();
  for (size_t n = 0; n < num_nodes; ++n) {
    if (g.nodes[n].index < (n == 0 ? 0 : g.nodes[n - 1].index + 1) ||
        g.nodes[n].index >= g.stats.nodes) {
      in->Fail("node indices are not increasing within the nodes added");
      return false;
    }
    // The path travelled only grows from node to node; NaN fails too.
    if (!(g.nodes[n].path_m >= (n == 0 ? 0.0 : g.nodes[n - 1].path_m)) ||
        !std::isfinite(g.nodes[n].path_m)) {
      in->Fail("node paths travelled are not increasing");
      return false;
    }
  }
  // Constraints and searches name nodes by index; a trimmed node may have left the graph.
  const auto held_node = [&g](int node) {
    const auto it = std::lower_bound(
        g.nodes.begin(), g.nodes.end(), node,
        [](const pose_graph::PoseGraphState2D::Node& n, int index) { return n.index < index; });
    return it != g.nodes.end() && it->index == node && !it->trimmed;
  };
  if (g.submaps.size() != num_submaps || g.T_map_submaps.size() != num_submaps ||
      g.T_map_nodes.size() != num_nodes) {
    in->Fail("the numbers of submaps and nodes disagree between the state's parts");
    return false;
  }
  for (size_t n = 0; n < num_nodes; ++n) {
    for (int s : g.nodes[n].inserted_into) {
      if (!InRange(s, num_submaps)) {
        in->Fail("node " + std::to_string(n) + " names missing submap " + std::to_string(s));
        return false;
      }
    }
  }
  for (size_t s = 0; s < num_submaps; ++s) {
    // Every pulse is one (node, submap) pair tried once, so there are at most as many as nodes.
    if (g.submaps[s].sampler_pulses < 0 ||
        g.submaps[s].sampler_pulses > g.stats.nodes) {
      in->Fail("submap " + std::to_string(s) + " sampler count is out of range");
      return false;
    }
    if (g.submaps[s].finished != state.submaps[s].finished) {
      in->Fail("submap " + std::to_string(s) + " finished flags disagree");
      return false;
    }
    // Path lengths only grow along the trajectory; NaN fails too.
    if (!(g.submaps[s].last_path_m >= g.submaps[s].first_path_m) ||
        !std::isfinite(g.submaps[s].last_path_m)) {
      in->Fail("submap " + std::to_string(s) + " path range is invalid");
      return false;
    }
    if (g.submaps[s].trimmed && !g.submaps[s].finished) {
      in->Fail("submap " + std::to_string(s) + " is trimmed but not finished");
      return false;
    }
  }
  for (const auto& c : g.constraints) {
    if (!InRange(c.submap, num_submaps) || !held_node(c.node) || g.submaps[c.submap].trimmed) {
      in->Fail("a constraint names a missing or trimmed node or submap");
      return false;
    }
  }
  for (const auto& search : g.searches_in_flight) {
    if (!InRange(search.submap, num_submaps) || !held_node(search.node) ||
        !g.submaps[search.submap].finished || g.submaps[search.submap].trimmed) {
      in->Fail("a pending search names a missing, trimmed or unfinished node or submap");
      return false;
    }
  }
  if (state.active_submaps.size() > 2) {
    in->Fail("more than two active submaps");
    return false;
  }
  for (int s : state.active_submaps) {
    if (!InRange(s, num_submaps) || g.submaps[s].trimmed) {
      in->Fail("active submap " + std::to_string(s) + " is missing or trimmed");
      return false;
    }
  }
  if (state.active_submaps.size() == 2 && state.active_submaps[0] == state.active_submaps[1]) {
    in->Fail("the two active submaps are the same");
    return false;
  }
  return true;
}

}  // namespace

bool DecodeMapBuilderState(ByteReader* in, pose_graph::MapBuilderState2D* state) {
  *state = pose_graph::MapBuilderState2D();
  // Minimum encoded sizes of list elements, for Count's allocation guard.
  constexpr size_t kSubmapBytes = 1;  // a trimmed one
  constexpr size_t kNodeBytes = 4 + 8 + 24 + 8 + 8 + 1 + 8;
  size_t n = 0;
  if (!in->Count(kSubmapBytes, &n)) return false;
  state->submaps.resize(n);
  std::vector<bool> has_grid(n, false);
  for (size_t s = 0; s < n; ++s) {
    bool present = false;
    if (!in->Bool(&present)) return false;
    has_grid[s] = present;
    state->submaps[s].finished = true;
    if (present && !DecodeSubmapState(in, &state->submaps[s])) return false;
  }
  pose_graph::PoseGraphState2D& g = state->pose_graph;
  if (!in->Count(kNodeBytes, &n)) return false;
  g.nodes.resize(n);
  for (auto& node : g.nodes) {
    if (!in->I32(&node.index) || !in->F64(&node.stamp_s) ||
        !DecodeRigid2d(in, &node.T_local_node) || !in->Count(8, &n)) {
      return false;
    }
    node.cloud.resize(n);
    for (auto& p : node.cloud) {
      if (!in->F32(&p.x()) || !in->F32(&p.y())) return false;
    }
    if (!in->Count(4, &n)) return false;
    node.inserted_into.resize(n);
    for (int& s : node.inserted_into) {
      if (!in->I32(&s)) return false;
    }
    if (!in->Bool(&node.trimmed) || !in->F64(&node.path_m)) return false;
  }
  if (!in->Count(27, &n)) return false;
  g.submaps.resize(n);
  for (size_t s = 0; s < n; ++s) {
    pose_graph::PoseGraphState2D::Submap& submap = g.submaps[s];
    int64_t pulses = 0;
    if (!in->Bool(&submap.finished) || !in->Bool(&submap.trimmed) ||
        !in->Bool(&submap.matcher_ready) || !in->I64(&pulses) ||
        !in->F64(&submap.first_path_m) || !in->F64(&submap.last_path_m)) {
      return false;
    }
    submap.sampler_pulses = static_cast<long>(pulses);
    if (s < has_grid.size() && submap.trimmed == has_grid[s]) {
      in->Fail("submap " + std::to_string(s) + " has a grid if and only if it is not trimmed");
      return false;
    }
  }
  for (auto* poses : {&g.T_map_nodes, &g.T_map_submaps}) {
    if (!in->Count(24, &n)) return false;
    poses->resize(n);
    for (auto& T : *poses) {
      if (!DecodeRigid2d(in, &T)) return false;
    }
  }
  if (!in->Count(86, &n)) return false;
  g.constraints.resize(n);
  for (auto& c : g.constraints) {
    uint8_t tag = 0, source = 0;
    double unmeasured_x = 0.0, unmeasured_y = 0.0;
    if (!in->I32(&c.submap) || !in->I32(&c.node) || !DecodeRigid2d(in, &c.T_submap_node) ||
        !in->F64(&c.translation_weight) || !in->F64(&c.rotation_weight) || !in->U8(&tag) ||
        !in->U8(&source) || !in->I32(&c.loop_id) || !in->F64(&c.laser_score) ||
        !in->F64(&unmeasured_x) || !in->F64(&unmeasured_y) ||
        !in->F64(&c.unmeasured_turn_rad_per_m)) {
      return false;
    }
    c.unmeasured_direction = Eigen::Vector2d(unmeasured_x, unmeasured_y);
    const double norm = c.unmeasured_direction.norm();
    if (!(norm == 0.0 || std::abs(norm - 1.0) < 1e-6)) {
      in->Fail("constraint unmeasured direction has length " + std::to_string(norm) +
               ", not 0 or 1");
      return false;
    }
    if (tag > pose_graph::Constraint2D::kLoopClosureCandidate) {
      in->Fail("constraint tag is " + std::to_string(tag) + ", not 0, 1 or 2");
      return false;
    }
    if (source > pose_graph::Constraint2D::kBoth) {
      in->Fail("constraint source is " + std::to_string(source) + ", not 0, 1 or 2");
      return false;
    }
    if (c.loop_id < -1) {
      in->Fail("constraint loop id " + std::to_string(c.loop_id) + " is below -1");
      return false;
    }
    c.tag = static_cast<pose_graph::Constraint2D::Tag>(tag);
    c.source = static_cast<pose_graph::Constraint2D::Source>(source);
  }
  if (!in->Count(32, &n)) return false;
  g.searches_in_flight.resize(n);
  for (auto& s : g.searches_in_flight) {
    if (!in->I32(&s.node) || !in->I32(&s.submap) || !DecodeRigid2d(in, &s.T_submap_node)) {
      return false;
    }
  }
  if (!in->Bool(&g.optimization_pending) || !in->I32(&g.nodes_since_optimization) ||
      !in->I32(&g.finished_submaps_at_last_trim) ||
      !in->U64(&g.solve_count) || !in->I32(&g.next_loop_id) || !GetStats(in, &g.stats) || !GetLocal(in, &state->local_slam) ||
      !in->Count(4, &n)) {
    return false;
  }
  state->active_submaps.resize(n);
  for (int& s : state->active_submaps) {
    if (!in->I32(&s)) return false;
  }
  if (!in->Count(48, &n)) return false;
  g.node_links.resize(n);
  for (auto& link : g.node_links) {
    if (!in->I32(&link.from) || !in->I32(&link.to) || !DecodeRigid2d(in, &link.T_from_to) ||
        !in->F64(&link.translation_weight) || !in->F64(&link.rotation_weight)) {
      return false;
    }
    if (!(link.from < link.to) || !(link.translation_weight > 0.0) ||
        !(link.rotation_weight > 0.0) || !std::isfinite(link.translation_weight) ||
        !std::isfinite(link.rotation_weight)) {
      in->Fail("node link " + std::to_string(link.from) + " -> " + std::to_string(link.to) +
               " is not forward with positive, finite weights");
      return false;
    }
  }
  return CheckInvariants(*state, in);
}

}  // namespace io
}  // namespace fusemap
