#ifndef FUSEMAP_POSE_GRAPH_ODOMETRY_CALIBRATION_H_
#define FUSEMAP_POSE_GRAPH_ODOMETRY_CALIBRATION_H_

#include <string>
#include <vector>

#include "fusemap/common/rigid_transform.h"
#include "fusemap/pose_graph/map_builder_2d.h"
#include "fusemap/sensor/sensor_types.h"

namespace fusemap {
namespace pose_graph {

// Systematic wheel-odometry errors of a differential drive (Borenstein & Feng 1996,
// "Measurement and correction of systematic odometry errors in mobile robots", IEEE T-RA
// 12(6)): the mean wheel diameter scales distance, the effective wheelbase scales rotation,
// and unequal wheel diameters bend a straight path, a heading change proportional to the
// distance driven. A corrected increment, in the frame of the earlier sample:
//   dtheta' = rotation_scale * dtheta + heading_drift_rad_per_m * d   (d signed: + forward)
//   t'      = translation_scale * R((dtheta' - dtheta) / 2) * t        (midpoint heading)
struct OdometryCalibration {
  double translation_scale = 1.0;
  double rotation_scale = 1.0;
  double heading_drift_rad_per_m = 0.0;

  bool IsIdentity() const;
};

struct OdometryCalibrationOptions {
  // Node-to-node intervals needed, and the motion they must cover, before the three parameters
  // are considered observable; with less the fit returns the identity.
  int min_intervals = 50;
  double min_distance_m = 10.0;
  double min_rotation_rad = 6.283185307179586;
  // A fit outside these bounds says the graph and the odometry disagree for another reason
  // (wrong frames, a broken graph); the identity is returned instead.
  double max_scale_deviation = 0.2;
  double max_heading_drift_rad_per_m = 0.2;
  // Iteratively reweighted least squares with Huber weights (Huber 1964; threshold in units of
  // the residuals' robust sigma, 1.4826 * median absolute residual).
  int robust_iterations = 5;
  double huber_threshold_sigma = 1.345;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// The increment `delta` (pose of a sample in the frame of the previous one), corrected.
common::Rigid2d CalibrateIncrement(const OdometryCalibration& calibration,
                                   const common::Rigid2d& delta);

// The odometry with every increment corrected, starting from the first sample's pose (same
// stamps). The identity returns the input unchanged.
std::vector<sensor::OdometryData> ApplyOdometryCalibration(
    const OdometryCalibration& calibration, const std::vector<sensor::OdometryData>& odometry);

// Fits the calibration to the motion between consecutive optimised nodes (SLAM's own estimate,
// no ground truth): heading parameters by robust linear least squares on the node-to-node
// heading change (exactly linear in them), then the translation scale on the
// heading-corrected odometry. Returns false, *calibration the identity and *reason filled when
// the data do not determine it (options' minimums) or the fit is out of bounds. `nodes` and
// `odometry` sorted by time.
bool FitOdometryCalibration(const std::vector<MapBuilder2D::TimedPose2d>& nodes,
                            const std::vector<sensor::OdometryData>& odometry,
                            const OdometryCalibrationOptions& options,
                            OdometryCalibration* calibration, std::string* reason);

}  // namespace pose_graph
}  // namespace fusemap

#endif  // FUSEMAP_POSE_GRAPH_ODOMETRY_CALIBRATION_H_
