#include "fusemap/sim/trajectory.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace fusemap {
namespace sim {

WaypointTrajectory::WaypointTrajectory(const RobotPlan& plan) {
  const std::vector<Eigen::Vector2d>& w = plan.waypoints_m;
  const int n = static_cast<int>(w.size());
  assert(n >= 3);
  std::vector<Eigen::Vector2d> arc_start(n), arc_end(n);
  std::vector<double> arc_turn(n, 0.0), arc_radius(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& prev = w[(i + n - 1) % n];
    const Eigen::Vector2d& cur = w[i];
    const Eigen::Vector2d& next = w[(i + 1) % n];
    const Eigen::Vector2d d_in = (cur - prev).normalized();
    const Eigen::Vector2d d_out = (next - cur).normalized();
    const double turn = std::atan2(d_in.x() * d_out.y() - d_in.y() * d_out.x(), d_in.dot(d_out));
    arc_start[i] = arc_end[i] = cur;
    if (std::abs(turn) < 1e-6) continue;
    const double half_tan = std::tan(0.5 * std::abs(turn));
    double tangent_m = plan.turn_radius_m * half_tan;
    // Leave part of each leg straight so consecutive arcs never overlap.
    tangent_m = std::min(tangent_m, 0.45 * std::min((cur - prev).norm(), (next - cur).norm()));
    arc_start[i] = cur - tangent_m * d_in;
    arc_end[i] = cur + tangent_m * d_out;
    arc_turn[i] = turn;
    arc_radius[i] = tangent_m / half_tan;
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const Eigen::Vector2d leg = arc_start[j] - arc_end[i];
    Piece line{arc_end[i], std::atan2(leg.y(), leg.x()), leg.norm(), 0.0};
    pieces_.push_back(line);
    if (arc_turn[j] != 0.0) {
      pieces_.push_back(Piece{arc_start[j], line.heading_rad, arc_radius[j] * std::abs(arc_turn[j]),
                              (arc_turn[j] > 0 ? 1.0 : -1.0) / arc_radius[j]});
    }
  }
  for (const Piece& piece : pieces_) loop_length_m_ += piece.length_m;

  const int samples = std::max(2, static_cast<int>(plan.laps * loop_length_m_ / ds_m_) + 1);
  speeds_mps_.resize(samples);
  for (int i = 0; i < samples; ++i) {
    Eigen::Vector2d p;
    double heading, curvature;
    Geometry(i * ds_m_, &p, &heading, &curvature);
    speeds_mps_[i] = plan.max_speed_mps;
    if (std::abs(curvature) > 1e-9) {
      speeds_mps_[i] = std::min(speeds_mps_[i],
                                std::sqrt(plan.max_lateral_accel_mps2 / std::abs(curvature)));
    }
  }
  // v^2 = v0^2 + 2 a ds, forwards from rest and backwards to rest.
  const double dv2 = 2.0 * plan.max_accel_mps2 * ds_m_;
  speeds_mps_.front() = 0.0;
  speeds_mps_.back() = 0.0;
  for (int i = 1; i < samples; ++i) {
    speeds_mps_[i] = std::min(speeds_mps_[i], std::sqrt(speeds_mps_[i - 1] * speeds_mps_[i - 1] + dv2));
  }
  for (int i = samples - 2; i >= 0; --i) {
    speeds_mps_[i] = std::min(speeds_mps_[i], std::sqrt(speeds_mps_[i + 1] * speeds_mps_[i + 1] + dv2));
  }
  stamps_s_.resize(samples, 0.0);
  for (int i = 1; i < samples; ++i) {
    stamps_s_[i] = stamps_s_[i - 1] + 2.0 * ds_m_ / (speeds_mps_[i - 1] + speeds_mps_[i]);
  }
}

void WaypointTrajectory::Geometry(double s_m, Eigen::Vector2d* position, double* heading_rad,
                                  double* curvature) const {
  double s = std::fmod(s_m, loop_length_m_);
  if (s < 0.0) s += loop_length_m_;
  const Piece* piece = &pieces_.back();
  for (const Piece& candidate : pieces_) {
    if (s <= candidate.length_m) {
      piece = &candidate;
      break;
    }
    s -= candidate.length_m;
  }
  s = std::min(s, piece->length_m);
  const double k = piece->curvature;
  const double h0 = piece->heading_rad;
  *curvature = k;
  *heading_rad = h0 + k * s;
  if (k == 0.0) {
    *position = piece->start + s * Eigen::Vector2d(std::cos(h0), std::sin(h0));
  } else {
    *position = piece->start + Eigen::Vector2d(std::sin(*heading_rad) - std::sin(h0),
                                               std::cos(h0) - std::cos(*heading_rad)) / k;
  }
}

RobotState WaypointTrajectory::StateAt(double stamp_s) const {
  const double t = std::clamp(stamp_s, 0.0, duration_s());
  size_t i = std::upper_bound(stamps_s_.begin(), stamps_s_.end(), t) - stamps_s_.begin();
  i = std::clamp<size_t>(i, 1, stamps_s_.size() - 1);
  const double dt = stamps_s_[i] - stamps_s_[i - 1];
  const double f = dt > 0.0 ? (t - stamps_s_[i - 1]) / dt : 0.0;
  const double v0 = speeds_mps_[i - 1], v1 = speeds_mps_[i];
  RobotState state;
  // Speed varies linearly in time between samples, so distance is the trapezoid.
  state.forward_accel_mps2 = (v1 * v1 - v0 * v0) / (2.0 * ds_m_);
  state.speed_mps = v0 + f * (v1 - v0);
  const double s = (i - 1) * ds_m_ + 0.5 * (v0 + state.speed_mps) * f * dt;
  Eigen::Vector2d position;
  double heading, curvature;
  Geometry(s, &position, &heading, &curvature);
  state.T_world_base = common::Rigid2d(position, heading);
  state.yaw_rate_radps = state.speed_mps * curvature;
  return state;
}

double WaypointTrajectory::TimeAtLaps(double laps) const {
  const double index = std::clamp(laps * loop_length_m_ / ds_m_, 0.0,
                                  static_cast<double>(stamps_s_.size() - 1));
  const size_t i = std::min(static_cast<size_t>(index), stamps_s_.size() - 2);
  return stamps_s_[i] + (index - i) * (stamps_s_[i + 1] - stamps_s_[i]);
}

}  // namespace sim
}  // namespace fusemap
