#ifndef FUSEMAP_CLOUD_CLOUD_TYPES_H_
#define FUSEMAP_CLOUD_CLOUD_TYPES_H_

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "fusemap/common/rigid_transform.h"

namespace fusemap {
namespace cloud {

// One point type for the whole binder, so PCL filters, writers and OctoMap export agree.
using ColorPoint = pcl::PointXYZRGB;
using ColorCloud = pcl::PointCloud<ColorPoint>;

// A filtered frame cloud in the colour camera's optical frame (z forward, x right, y down),
// with where the camera sat on the robot base when it was taken.
struct CameraCloud {
  double stamp_s = 0.0;
  ColorCloud::Ptr points_camera;
  common::Rigid3d T_base_camera;
};

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_CLOUD_TYPES_H_
