#include "fusemap/sim/rgbd_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "fusemap/common/math.h"
#include "fusemap/sim/ray_cast_2d.h"
#include "random.h"
#include "texture.h"

namespace fusemap {
namespace sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxCandidates = 32;
constexpr int kTagSupersampling = 4;  // Per axis, for pixels near a tag: anti-aliased edges.

struct Hit {
  enum class Kind { kNone, kFloor, kCeiling, kSide, kTop };
  Kind kind = Kind::kNone;
  double lambda = 0.0;  // Point = origin + lambda * d with d's optical z = 1: the depth.
  int prism = -1;
  int face = 0;
  double u_m = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

struct Crossing {
  FootprintCrossing crossing;
  int prism;
};

// Casts the ray origin + t * d (world frame) against floor (z = 0), ceiling and the candidate
// prisms, in front-to-back order of the footprint crossings.
Hit Trace(const World& world, const std::vector<Prism>& prisms, const std::vector<int>& candidates,
          const Eigen::Vector3d& origin, const Eigen::Vector3d& d) {
  Hit hit;
  const double h = std::hypot(d.x(), d.y());
  if (h < 1e-12) return hit;
  const Eigen::Vector2d dir2(d.x() / h, d.y() / h);
  const double slope = d.z() / h;  // dz per horizontal metre.
  double best = kInf;
  if (slope < 0.0) {
    best = -origin.z() / slope;
    hit.kind = Hit::Kind::kFloor;
  } else if (slope > 0.0) {
    best = (world.ceiling_height_m - origin.z()) / slope;
    hit.kind = Hit::Kind::kCeiling;
  }
  Crossing crossings[kMaxCandidates];
  int n = 0;
  for (int index : candidates) {
    if (n == kMaxCandidates) break;
    if (IntersectFootprint(prisms[index], origin.head<2>(), dir2, &crossings[n].crossing)) {
      crossings[n++].prism = index;
    }
  }
  std::sort(crossings, crossings + n, [](const Crossing& a, const Crossing& b) {
    return a.crossing.t_in < b.crossing.t_in;
  });
  for (int i = 0; i < n; ++i) {
    const FootprintCrossing& c = crossings[i].crossing;
    if (c.t_in >= best) break;
    const Prism& prism = prisms[crossings[i].prism];
    const double z_in = origin.z() + slope * c.t_in;
    if (z_in >= prism.z_min_m && z_in <= prism.z_max_m) {
      best = c.t_in;
      hit.kind = Hit::Kind::kSide;
    } else if (z_in > prism.z_max_m && slope < 0.0) {
      const double t_top = (prism.z_max_m - origin.z()) / slope;
      if (t_top > c.t_out) continue;
      best = t_top;
      hit.kind = Hit::Kind::kTop;
    } else if (z_in < prism.z_min_m && slope > 0.0) {
      const double t_bottom = (prism.z_min_m - origin.z()) / slope;
      if (t_bottom > c.t_out) continue;
      best = t_bottom;
      hit.kind = Hit::Kind::kTop;
    } else {
      continue;
    }
    hit.prism = crossings[i].prism;
    hit.face = c.face_in;
    hit.u_m = c.u_in_m;
    break;
  }
  if (!std::isfinite(best)) return Hit();
  hit.lambda = best / h;
  hit.point = origin + hit.lambda * d;
  return hit;
}

Eigen::Vector3f FloorColor(const World& world, const FloorTags* tags, const Eigen::Vector2d& p) {
  float reflectance;
  if (tags != nullptr && tags->Reflectance(p, &reflectance)) {
    const float level = 15.f + reflectance * 225.f;
    return Eigen::Vector3f(level, level, level);
  }
  const double tile = world.floor_tile_m;
  const double fx = p.x() / tile - std::floor(p.x() / tile);
  const double fy = p.y() / tile - std::floor(p.y() / tile);
  const double grout = 0.012 / tile;
  if (fx < grout || fy < grout) return 0.55f * world.floor_color;
  const double variation = HashToUnit(world.floor_seed, static_cast<uint64_t>(std::floor(p.x() / tile)),
                                      static_cast<uint64_t>(std::floor(p.y() / tile)));
  return static_cast<float>(0.82 + 0.2 * variation) * world.floor_color;
}

Eigen::Vector3f CeilingColor(const World& world, const Eigen::Vector3d& p) {
  // Light panels every 2.4 m give the ceiling some structure.
  const double fx = p.x() / 2.4 - std::floor(p.x() / 2.4);
  const double fy = p.y() / 2.4 - std::floor(p.y() / 2.4);
  const bool panel = fx > 0.3 && fx < 0.7 && fy > 0.4 && fy < 0.6;
  return panel ? Eigen::Vector3f(255.f, 255.f, 250.f) : 0.85f * world.ceiling_color;
}

Eigen::Vector3f ShadeHit(const World& world, const std::vector<Prism>& prisms, const Hit& hit) {
  switch (hit.kind) {
    case Hit::Kind::kNone:
      return Eigen::Vector3f(0.f, 0.f, 0.f);
    case Hit::Kind::kFloor:
      return FloorColor(world, nullptr, hit.point.head<2>());  // Tags: see RenderView.
    case Hit::Kind::kCeiling:
      return CeilingColor(world, hit.point);
    case Hit::Kind::kTop:
      return SampleTexture(prisms[hit.prism].top_texture, hit.point.x(), hit.point.y());
    case Hit::Kind::kSide:
      break;
  }
  const Prism& prism = prisms[hit.prism];
  Eigen::Vector2d normal;
  if (prism.shape == Prism::Shape::kCircle) {
    normal = (hit.point.head<2>() - prism.centre_m).normalized();
  } else {
    const double angle = prism.yaw_rad + 0.5 * common::kPi * hit.face;
    normal = Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  // Fixed directional light, so faces of different orientation differ in brightness.
  const double lambert = std::max(0.0, normal.dot(Eigen::Vector2d(0.6, 0.8)));
  const float shade = static_cast<float>(0.6 + 0.4 * lambert);
  return shade * SampleTexture(prism.side_textures[prism.shape == Prism::Shape::kCircle ? 0 : hit.face],
                               hit.u_m, hit.point.z());
}

// Per azimuth bin (uniform in tan(azimuth - yaw_rad)), the prisms the pixel rays of that bin may hit: everything crossed by the two
// bin-edge rays up to the first floor-to-ceiling prism. Exact tests happen per pixel.
std::vector<std::vector<int>> BinCandidates(const World& world, const std::vector<Prism>& prisms,
                                            const Eigen::Vector2d& origin, double yaw_rad,
                                            double rel_min, double bin_width, int num_bins) {
  std::vector<std::vector<int>> edges(num_bins + 1);
  std::vector<Crossing> crossings;
  for (int k = 0; k <= num_bins; ++k) {
    const double az = yaw_rad + std::atan(rel_min + k * bin_width);
    const Eigen::Vector2d dir(std::cos(az), std::sin(az));
    crossings.clear();
    Crossing c;
    for (size_t i = 0; i < prisms.size(); ++i) {
      if (IntersectFootprint(prisms[i], origin, dir, &c.crossing)) {
        c.prism = static_cast<int>(i);
        crossings.push_back(c);
      }
    }
    std::sort(crossings.begin(), crossings.end(), [](const Crossing& a, const Crossing& b) {
      return a.crossing.t_in < b.crossing.t_in;
    });
    for (const Crossing& crossing : crossings) {
      edges[k].push_back(crossing.prism);
      const Prism& p = prisms[crossing.prism];
      if (p.z_min_m <= 0.0 && p.z_max_m >= world.ceiling_height_m) break;
    }
  }
  std::vector<std::vector<int>> bins(num_bins);
  for (int k = 0; k < num_bins; ++k) {
    bins[k] = edges[k];
    for (int index : edges[k + 1]) {
      if (std::find(bins[k].begin(), bins[k].end(), index) == bins[k].end()) bins[k].push_back(index);
    }
  }
  return bins;
}

}  // namespace

void RenderView(const World& world, const std::vector<Prism>& prisms, const FloorTags& tags,
                const common::Rigid3d& T_world_camera, const sensor::PinholeIntrinsics& intrinsics,
                std::vector<uint8_t>* color_rgb, std::vector<float>* depth_m) {
  const int w = intrinsics.width, h = intrinsics.height;
  const Eigen::Matrix3d R = T_world_camera.rotation().toRotationMatrix();
  const Eigen::Vector3d origin = T_world_camera.translation();
  auto ray = [&](double u, double v) -> Eigen::Vector3d {
    Eigen::Vector3d d_camera;
    d_camera << (u - intrinsics.cx) / intrinsics.fx, (v - intrinsics.cy) / intrinsics.fy, 1.0;
    return R * d_camera;
  };
  const Eigen::Vector3d forward = R.col(2);
  const double yaw = std::atan2(forward.y(), forward.x());
  const Eigen::Vector2d ahead(std::cos(yaw), std::sin(yaw));
  // Bins are uniform in the tangent of the azimuth relative to the view direction: monotonic
  // over the field of view (< 180 deg) and much cheaper than atan2 per pixel.
  auto relative_azimuth = [&](const Eigen::Vector3d& d) {
    return (ahead.x() * d.y() - ahead.y() * d.x()) / (ahead.x() * d.x() + ahead.y() * d.y());
  };
  // Azimuth extremes lie on the image border (the camera has no roll w.r.t. the floor).
  double rel_min = kInf, rel_max = -kInf;
  for (int u = 0; u < w; ++u) {
    for (int v : {0, h - 1}) {
      const double a = relative_azimuth(ray(u, v));
      rel_min = std::min(rel_min, a);
      rel_max = std::max(rel_max, a);
    }
  }
  const int num_bins = 2 * w;
  const double bin_width = (rel_max - rel_min) / num_bins + 1e-12;
  const std::vector<std::vector<int>> bins =
      BinCandidates(world, prisms, origin.head<2>(), yaw, rel_min, bin_width, num_bins);

  if (color_rgb != nullptr) color_rgb->assign(3 * w * h, 0);
  if (depth_m != nullptr) depth_m->assign(w * h, 0.f);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d d = ray(u, v);
      const int bin = std::clamp(static_cast<int>((relative_azimuth(d) - rel_min) / bin_width), 0, num_bins - 1);
      const Hit hit = Trace(world, prisms, bins[bin], origin, d);
      if (depth_m != nullptr) (*depth_m)[v * w + u] = static_cast<float>(hit.lambda);
      if (color_rgb == nullptr) continue;
      Eigen::Vector3f color = ShadeHit(world, prisms, hit);
      if (hit.kind == Hit::Kind::kFloor && tags.Near(hit.point.head<2>())) {
        // Box-filter the pixel footprint on the floor plane (all samples stay on the floor).
        color.setZero();
        for (int i = 0; i < kTagSupersampling; ++i) {
          for (int j = 0; j < kTagSupersampling; ++j) {
            const Eigen::Vector3d ds = ray(u - 0.5 + (i + 0.5) / kTagSupersampling,
                                           v - 0.5 + (j + 0.5) / kTagSupersampling);
            const Eigen::Vector3d p = origin - (origin.z() / ds.z()) * ds;
            color += FloorColor(world, &tags, p.head<2>());
          }
        }
        color /= static_cast<float>(kTagSupersampling * kTagSupersampling);
      }
      for (int c = 0; c < 3; ++c) {
        (*color_rgb)[3 * (v * w + u) + c] =
            static_cast<uint8_t>(std::clamp(std::lround(color[c]), 0L, 255L));
      }
    }
  }
}

void RgbdCameraOptions::Check(common::OptionChecker* check) const {
  check->Require(rate_hz > 0.0, "rate_hz", "must be > 0");
  check->Require(width >= 8 && width <= 4096, "width", "must be in [8, 4096]");
  check->Require(height >= 8 && height <= 4096, "height", "must be in [8, 4096]");
  check->Require(fx > 0.0, "fx", "must be > 0");
  check->Require(fy > 0.0, "fy", "must be > 0");
  check->Require(mount_z_m > 0.0, "mount_z_m", "must be > 0 (camera above the floor)");
  check->Require(pitch_down_deg > -80.0 && pitch_down_deg < 80.0, "pitch_down_deg",
                 "must be in (-80, 80)");
  check->Require(depth_min_m > 0.0, "depth_min_m", "must be > 0");
  check->Require(depth_max_m > depth_min_m && depth_max_m < 65.0, "depth_max_m",
                 "must be > depth_min_m and < 65");
  check->Require(depth_noise_k_per_m >= 0.0, "depth_noise_k_per_m", "must be >= 0");
}

bool RgbdCameraOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

RgbdCameraOptions ParseRgbdCameraOptions(common::ConfigReader& reader) {
  RgbdCameraOptions o;
  reader.Get("rate_hz", &o.rate_hz);
  reader.Get("width", &o.width);
  reader.Get("height", &o.height);
  reader.Get("fx", &o.fx);
  reader.Get("fy", &o.fy);
  reader.Get("cx", &o.cx);
  reader.Get("cy", &o.cy);
  reader.Get("mount_x_m", &o.mount_x_m);
  reader.Get("mount_y_m", &o.mount_y_m);
  reader.Get("mount_z_m", &o.mount_z_m);
  reader.Get("pitch_down_deg", &o.pitch_down_deg);
  reader.Get("depth_baseline_m", &o.depth_baseline_m);
  reader.Get("depth_min_m", &o.depth_min_m);
  reader.Get("depth_max_m", &o.depth_max_m);
  reader.Get("depth_noise_k_per_m", &o.depth_noise_k_per_m);
  reader.CheckOptions(o);
  return o;
}

sensor::PinholeIntrinsics Intrinsics(const RgbdCameraOptions& o) {
  sensor::PinholeIntrinsics k;
  k.width = o.width;
  k.height = o.height;
  k.fx = o.fx;
  k.fy = o.fy;
  k.cx = o.cx;
  k.cy = o.cy;
  return k;
}

common::Rigid3d TBaseColor(const RgbdCameraOptions& o) {
  // Optical axes in the base frame (x right = -y_base, y down = -z_base, z forward = x_base),
  // then pitched down about the base y axis.
  Eigen::Matrix3d R_base_optical;
  R_base_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  const Eigen::Quaterniond pitch(Eigen::AngleAxisd(common::DegToRad(o.pitch_down_deg), Eigen::Vector3d::UnitY()));
  return common::Rigid3d(Eigen::Vector3d(o.mount_x_m, o.mount_y_m, o.mount_z_m),
                         pitch * Eigen::Quaterniond(R_base_optical));
}

common::Rigid3d TColorDepth(const RgbdCameraOptions& o) {
  return common::Rigid3d(Eigen::Vector3d(-o.depth_baseline_m, 0.0, 0.0), Eigen::Quaterniond::Identity());
}

sensor::RgbdFrame RenderRgbdFrame(const World& world, const std::vector<Prism>& prisms,
                                  const FloorTags& tags, const common::Rigid2d& T_world_base,
                                  double stamp_s, const RgbdCameraOptions& options, uint64_t seed,
                                  uint64_t frame_index) {
  sensor::RgbdFrame frame;
  frame.stamp_s = stamp_s;
  frame.color_intrinsics = Intrinsics(options);
  frame.depth_intrinsics = frame.color_intrinsics;
  frame.T_base_color = TBaseColor(options);
  frame.T_color_depth = TColorDepth(options);
  const common::Rigid3d T_world_color = common::Rigid3d::FromRigid2d(T_world_base) * frame.T_base_color;
  RenderView(world, prisms, tags, T_world_color, frame.color_intrinsics, &frame.color_rgb, nullptr);
  std::vector<float> depth_m;
  const common::Rigid3d T_world_depth = T_world_color * frame.T_color_depth;
  RenderView(world, prisms, tags, T_world_depth, frame.depth_intrinsics, nullptr, &depth_m);

  std::mt19937_64 rng = MakeRng(seed, NoiseStream::kDepth, frame_index);
  std::normal_distribution<double> unit(0.0, 1.0);
  const Eigen::Matrix3d R = T_world_depth.rotation().toRotationMatrix();
  const sensor::PinholeIntrinsics& k = frame.depth_intrinsics;
  frame.depth_mm.assign(depth_m.size(), 0);
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const double z = depth_m[v * k.width + u];
      if (z < options.depth_min_m || z > options.depth_max_m) continue;
      const double noisy = z + options.depth_noise_k_per_m * z * z * unit(rng);
      Eigen::Vector3d d_camera;
      d_camera << (u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0;
      const Eigen::Vector3d p = T_world_depth.translation() + z * (R * d_camera);
      bool dropped = false;
      for (const DepthDropoutZone& zone : world.depth_dropout_zones) {
        dropped = dropped || (p.x() >= zone.min_m.x() && p.x() <= zone.max_m.x() &&
                              p.y() >= zone.min_m.y() && p.y() <= zone.max_m.y());
      }
      if (dropped || noisy <= 0.0) continue;
      frame.depth_mm[v * k.width + u] = static_cast<uint16_t>(std::min(65535L, std::lround(noisy * 1000.0)));
    }
  }
  return frame;
}

void ApplyLighting(const LightingPhase& lighting, uint64_t seed, uint64_t frame_index,
                   std::vector<uint8_t>* color_rgb) {
  if (lighting.gain == 1.0 && lighting.bias == 0.0 && lighting.noise_std == 0.0) return;
  std::mt19937_64 rng = MakeRng(seed, NoiseStream::kColor, frame_index);
  std::normal_distribution<double> noise(0.0, lighting.noise_std);
  for (uint8_t& value : *color_rgb) {
    double v = lighting.gain * value + lighting.bias;
    if (lighting.noise_std > 0.0) v += noise(rng);
    value = static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L));
  }
}

}  // namespace sim
}  // namespace fusemap
