#ifndef FUSEMAP_COMMON_RIGID_TRANSFORM_H_
#define FUSEMAP_COMMON_RIGID_TRANSFORM_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "fusemap/common/math.h"

namespace fusemap {
namespace common {

// A rigid motion in the plane. Names of variables holding one say their frames:
// T_map_submap maps submap coordinates into the map frame, so
// T_a_c = T_a_b * T_b_c and p_a = T_a_b * p_b. The angle is kept normalised to [-pi, pi).
class Rigid2d {
 public:
  Rigid2d() : translation_(Eigen::Vector2d::Zero()), angle_rad_(0.0) {}
  Rigid2d(const Eigen::Vector2d& translation, double angle_rad)
      : translation_(translation), angle_rad_(NormalizeAngle(angle_rad)) {}
  Rigid2d(double x_m, double y_m, double angle_rad)
      : Rigid2d(Eigen::Vector2d(x_m, y_m), angle_rad) {}

  static Rigid2d Identity() { return Rigid2d(); }
  static Rigid2d Translation(const Eigen::Vector2d& t) { return Rigid2d(t, 0.0); }
  static Rigid2d Rotation(double angle_rad) { return Rigid2d(Eigen::Vector2d::Zero(), angle_rad); }

  const Eigen::Vector2d& translation() const { return translation_; }
  double x() const { return translation_.x(); }
  double y() const { return translation_.y(); }
  double angle_rad() const { return angle_rad_; }
  Eigen::Rotation2Dd rotation() const { return Eigen::Rotation2Dd(angle_rad_); }

  Rigid2d inverse() const {
    const Eigen::Rotation2Dd inv_rot(-angle_rad_);
    return Rigid2d(-(inv_rot * translation_), -angle_rad_);
  }

  Rigid2d operator*(const Rigid2d& rhs) const {
    return Rigid2d(translation_ + rotation() * rhs.translation_, angle_rad_ + rhs.angle_rad_);
  }
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const {
    return rotation() * p + translation_;
  }
  Eigen::Vector2f operator*(const Eigen::Vector2f& p) const {
    return (rotation() * p.cast<double>() + translation_).cast<float>();
  }

  std::string DebugString() const;

 private:
  Eigen::Vector2d translation_;
  double angle_rad_;
};

// A rigid motion in space; same naming convention as Rigid2d.
class Rigid3d {
 public:
  Rigid3d() : translation_(Eigen::Vector3d::Zero()), rotation_(Eigen::Quaterniond::Identity()) {}
  Rigid3d(const Eigen::Vector3d& translation, const Eigen::Quaterniond& rotation)
      : translation_(translation), rotation_(rotation.normalized()) {}

  static Rigid3d Identity() { return Rigid3d(); }
  // The planar motion lifted to 3D (rotation about +z).
  static Rigid3d FromRigid2d(const Rigid2d& pose);
  // Drops roll, pitch and z: the projection used when a 3D pose drives 2D SLAM.
  Rigid2d ToRigid2d() const;

  const Eigen::Vector3d& translation() const { return translation_; }
  const Eigen::Quaterniond& rotation() const { return rotation_; }

  Rigid3d inverse() const {
    const Eigen::Quaterniond inv = rotation_.conjugate();
    return Rigid3d(-(inv * translation_), inv);
  }
  Rigid3d operator*(const Rigid3d& rhs) const {
    return Rigid3d(translation_ + rotation_ * rhs.translation_, rotation_ * rhs.rotation_);
  }
  Eigen::Vector3d operator*(const Eigen::Vector3d& p) const { return rotation_ * p + translation_; }

  std::string DebugString() const;

 private:
  Eigen::Vector3d translation_;
  Eigen::Quaterniond rotation_;
};

// Yaw of a rotation about +z, in [-pi, pi).
double YawFromQuaternion(const Eigen::Quaterniond& q);

// Linear interpolation of translation and angle (shortest way round); fraction in [0, 1].
Rigid2d Interpolate(const Rigid2d& a, const Rigid2d& b, double fraction);
// Linear interpolation of translation, slerp of rotation; fraction in [0, 1].
Rigid3d Interpolate(const Rigid3d& a, const Rigid3d& b, double fraction);

}  // namespace common
}  // namespace fusemap

#endif  // FUSEMAP_COMMON_RIGID_TRANSFORM_H_
