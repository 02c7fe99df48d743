#include "fusemap/sim/laser_simulator.h"

#include <cmath>

#include "fusemap/common/math.h"
#include "fusemap/sim/ray_cast_2d.h"

namespace fusemap {
namespace sim {
void LaserOptions::Check(common::OptionChecker* check) const {
  check->Require(rate_hz > 0.0 && rate_hz <= 1000.0, "rate_hz", "must be in (0, 1000]");
  check->Require(fov_deg > 0.0 && fov_deg <= 360.0, "fov_deg", "must be in (0, 360]");
  check->Require(num_beams >= 2, "num_beams", "must be >= 2");
  check->Require(range_min_m >= 0.0, "range_min_m", "must be >= 0");
  check->Require(range_max_m > range_min_m, "range_max_m", "must be > range_min_m");
  check->Require(range_noise_stddev_m >= 0.0, "range_noise_stddev_m", "must be >= 0");
}

bool LaserOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

LaserOptions ParseLaserOptions(common::ConfigReader& reader) {
  LaserOptions options;
  reader.Get("rate_hz", &options.rate_hz);
  reader.Get("fov_deg", &options.fov_deg);
  reader.Get("num_beams", &options.num_beams);
  reader.Get("range_min_m", &options.range_min_m);
  reader.Get("range_max_m", &options.range_max_m);
  reader.Get("range_noise_stddev_m", &options.range_noise_stddev_m);
  reader.Get("mount_height_m", &options.mount_height_m);
  reader.CheckOptions(options);
  return options;
}

sensor::LaserScan SimulateLaserScan(const std::vector<Prism>& prisms,
                                    const common::Rigid2d& T_world_base, double stamp_s,
                                    const LaserOptions& options, std::mt19937_64* rng) {
  sensor::LaserScan scan;
  scan.stamp_s = stamp_s;
  scan.frame = "laser";
  const double fov_rad = common::DegToRad(options.fov_deg);
  scan.angle_min_rad = static_cast<float>(-0.5 * fov_rad);
  scan.angle_increment_rad = static_cast<float>(fov_rad / (options.num_beams - 1));
  scan.range_min_m = static_cast<float>(options.range_min_m);
  scan.range_max_m = static_cast<float>(options.range_max_m);
  scan.ranges_m.resize(options.num_beams);
  std::normal_distribution<double> noise(0.0, options.range_noise_stddev_m);
  for (int i = 0; i < options.num_beams; ++i) {
    const double angle = T_world_base.angle_rad() + scan.angle_min_rad +
                         static_cast<double>(i) * scan.angle_increment_rad;
    int hit = -1;
    double range = CastRay2d(prisms, T_world_base.translation(),
                             Eigen::Vector2d(std::cos(angle), std::sin(angle)),
                             options.mount_height_m, options.range_max_m, &hit);
    // Always draw, so the noise of beam i does not depend on whether other beams hit.
    const double n = options.range_noise_stddev_m > 0.0 ? noise(*rng) : 0.0;
    if (hit >= 0) range += n;
    if (hit < 0 || range < options.range_min_m || range >= options.range_max_m) {
      range = options.range_max_m;
    }
    scan.ranges_m[i] = static_cast<float>(range);
  }
  return scan;
}

}  // namespace sim
}  // namespace fusemap
