#ifndef FUSEMAP_SIM_LASER_SIMULATOR_H_
#define FUSEMAP_SIM_LASER_SIMULATOR_H_

#include <random>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"
#include "fusemap/common/rigid_transform.h"
#include "fusemap/sensor/sensor_types.h"
#include "fusemap/sim/world.h"

namespace fusemap {
namespace sim {

// A planar scanner at height mount_height_m, with the laser frame at the base origin (the
// scan is in base coordinates; "laser" frame == base frame in x, y, yaw).
struct LaserOptions {
  double rate_hz = 25.0;
  double fov_deg = 270.0;
  int num_beams = 811;  // 270 deg / 810 = 0.333 deg steps.
  double range_min_m = 0.1;
  double range_max_m = 12.0;
  double range_noise_stddev_m = 0.01;
  double mount_height_m = 0.3;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};
LaserOptions ParseLaserOptions(common::ConfigReader& reader);

// One noisy scan of `prisms` from T_world_base. Beams that hit nothing within range_max_m (or
// land outside the limits after noise) read range_max_m, i.e. "no return".
sensor::LaserScan SimulateLaserScan(const std::vector<Prism>& prisms,
                                    const common::Rigid2d& T_world_base, double stamp_s,
                                    const LaserOptions& options, std::mt19937_64* rng);

}  // namespace sim
}  // namespace fusemap

#endif  // FUSEMAP_SIM_LASER_SIMULATOR_H_
