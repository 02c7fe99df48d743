#include "fusemap/common/rigid_transform.h"

#include <cstdio>

namespace fusemap {
namespace common {

Rigid3d Rigid3d::FromRigid2d(const Rigid2d& pose) {
  return Rigid3d(Eigen::Vector3d(pose.x(), pose.y(), 0.0),
                 Eigen::Quaterniond(Eigen::AngleAxisd(pose.angle_rad(), Eigen::Vector3d::UnitZ())));
}

Rigid2d Rigid3d::ToRigid2d() const {
  return Rigid2d(translation_.head<2>(), YawFromQuaternion(rotation_));
}

std::string Rigid2d::DebugString() const {
  char buf[128];
  std::snprintf(buf, sizeof(buf), "{x=%.4f y=%.4f a=%.5f}", x(), y(), angle_rad_);
  return buf;
}

std::string Rigid3d::DebugString() const {
  char buf[192];
  std::snprintf(buf, sizeof(buf), "{t=[%.4f %.4f %.4f] q=[%.5f %.5f %.5f %.5f]}", translation_.x(),
                translation_.y(), translation_.z(), rotation_.w(), rotation_.x(), rotation_.y(),
                rotation_.z());
  return buf;
}

double YawFromQuaternion(const Eigen::Quaterniond& q) {
  // Standard ZYX extraction; exact for a pure yaw and the planar projection otherwise.
  return NormalizeAngle(std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()),
                                   1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z())));
}

Rigid2d Interpolate(const Rigid2d& a, const Rigid2d& b, double fraction) {
  const Eigen::Vector2d t = a.translation() + fraction * (b.translation() - a.translation());
  const double d_angle = NormalizeAngle(b.angle_rad() - a.angle_rad());
  return Rigid2d(t, a.angle_rad() + fraction * d_angle);
}

Rigid3d Interpolate(const Rigid3d& a, const Rigid3d& b, double fraction) {
  const Eigen::Vector3d t = a.translation() + fraction * (b.translation() - a.translation());
  return Rigid3d(t, a.rotation().slerp(fraction, b.rotation()));
}

}  // namespace common
}  // namespace fusemap
