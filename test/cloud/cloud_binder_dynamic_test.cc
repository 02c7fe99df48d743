// Dynamic object removal of CloudBinder on ray-cast synthetic scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "fusemap/cloud/cloud_binder.h"

namespace fusemap {
namespace cloud {
namespace {

using common::Rigid3d;

struct Box {
  Eigen::Vector3d min;
  Eigen::Vector3d max;
  bool Contains(const Eigen::Vector3f& p, double pad_m) const {
    const Eigen::Vector3d q = p.cast<double>();
    return (q.array() >= min.array() - pad_m).all() && (q.array() <= max.array() + pad_m).all();
  }
};

// Slab test; returns the entry distance or +inf.
double IntersectBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& box) {
  double t_near = 0.0, t_far = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (o[i] < box.min[i] || o[i] > box.max[i]) return std::numeric_limits<double>::infinity();
      continue;
    }
    double t0 = (box.min[i] - o[i]) / d[i], t1 = (box.max[i] - o[i]) / d[i];
    if (t0 > t1) std::swap(t0, t1);
    t_near = std::max(t_near, t0);
    t_far = std::min(t_far, t1);
  }
  return t_near <= t_far ? t_near : std::numeric_limits<double>::infinity();
}

// Camera at `position` looking along map yaw `yaw_rad`, optical frame (z forward, y down).
// These tests exercise the ray-casting carver (AddCloud carves with each cloud's own rays);
// projective carving against depth images is tested in depth_carver_test.cc.
CloudBinderOptions RayCarvingOptions() {
  CloudBinderOptions options;
  options.ray_carving = true;
  return options;
}

Rigid3d CameraPose(const Eigen::Vector3d& position, double yaw_rad) {
  Eigen::Matrix3d R_base_optical;
  R_base_optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return Rigid3d(position, Eigen::Quaterniond(Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                                              R_base_optical));
}

// Renders the nearest box along each pixel ray (about a 64 x 50 degree field of view, 0.2-5.5 m,
// 5 mm depth noise) into a camera-frame cloud, as the per-frame pipeline would hand it over.
CameraCloud Render(const std::vector<Box>& boxes, const Rigid3d& T_map_camera, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, 0.005);
  CameraCloud cloud;
  cloud.points_camera.reset(new ColorCloud);
  const Eigen::Vector3d o = T_map_camera.translation();
  for (double v = -0.44; v <= 0.44; v += 0.006) {
    for (double u = -0.56; u <= 0.56; u += 0.006) {
      const Eigen::Vector3d d_camera = Eigen::Vector3d(std::tan(u), std::tan(v), 1.0).normalized();
      const Eigen::Vector3d d_map = T_map_camera.rotation() * d_camera;
      double t = std::numeric_limits<double>::infinity();
      for (const Box& box : boxes) t = std::min(t, IntersectBox(o, d_map, box));
      if (t < 0.2 || t > 5.5) continue;
      ColorPoint p;
      p.getVector3fMap() = ((t + noise(*rng)) * d_camera).cast<float>();
      p.r = p.g = p.b = 128;
      cloud.points_camera->push_back(p);
    }
  }
  return cloud;
}

struct Kept {
  size_t kept = 0;
  size_t removed = 0;
  double KeptFraction() const {
    return kept + removed == 0 ? 0.0 : double(kept) / (kept + removed);
  }
};

void Report(const char* what, const Kept& counts) {
  std::printf("%s: kept=%zu removed=%zu kept_frac=%.4f\n", what, counts.kept, counts.removed,
              counts.KeptFraction());
}

Kept CountIn(const CloudBinder& binder, const Box& box, double pad_m) {
  Kept counts;
  const ColorCloud::Ptr global = binder.GlobalCloud();
  for (const ColorPoint& p : global->points) {
    if (box.Contains(p.getVector3fMap(), pad_m)) ++counts.kept;
  }
  for (const ColorPoint& p : binder.removed_points().points) {
    if (box.Contains(p.getVector3fMap(), pad_m)) ++counts.removed;
  }
  return counts;
}

TEST(CloudBinderDynamicTest, PersonSeenOnceThenSeenThroughIsRemovedWallKept) {
  const Box wall{{4.0, -2.5, 0.0}, {4.1, 2.5, 3.5}};
  const Box floor{{-1.0, -2.5, -0.1}, {4.0, 2.5, 0.0}};
  const Box person{{2.0, -0.3, 0.0}, {2.4, 0.3, 1.8}};
  CloudBinder binder{RayCarvingOptions()};
  // The second frame is bound to another submap: carving must cross regions.
  const Rigid3d T_map_submap1(Eigen::Vector3d(0.5, 0.2, 0.0),
                              Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ())));
  binder.SetSubmapPose(0, Rigid3d::Identity());
  binder.SetSubmapPose(1, T_map_submap1);
  std::mt19937 rng(1);
  const Rigid3d T_map_camera1 = CameraPose({0.0, 0.0, 1.0}, 0.0);
  binder.AddCloud(0, T_map_camera1, Render({wall, floor, person}, T_map_camera1, &rng));
  const size_t person_before = CountIn(binder, person, 0.03).kept;
  ASSERT_GT(person_before, 500u);

  const Rigid3d T_map_camera2 = CameraPose({-0.3, 0.1, 1.0}, 0.05);
  binder.AddCloud(1, T_map_submap1.inverse() * T_map_camera2,
                  Render({wall, floor}, T_map_camera2, &rng));

  // The person's lowest voxel row touches the floor the second frame sees, so it is kept on
  // purpose (a surface observed now is never carved); count the person from 3 cm up.
  const Box person_probe{{2.0, -0.3, 0.06}, {2.4, 0.3, 1.8}};
  const Kept person_counts = CountIn(binder, person_probe, 0.03);
  const Kept wall_counts = CountIn(binder, wall, 0.03);
  Report("person", person_counts);
  Report("wall", wall_counts);
  std::printf("last_carve_ms=%.1f last_frame_ms=%.1f\n", binder.stats().last_carve_ms,
              binder.stats().last_frame_ms);
  EXPECT_GE(1.0 - person_counts.KeptFraction(), 0.95)
      << person_counts.kept << " person points left of " << person_before;
  EXPECT_GE(wall_counts.KeptFraction(), 0.99) << wall_counts.removed << " wall points removed";
  const Kept floor_counts = CountIn(binder, floor, 0.02);
  EXPECT_GE(floor_counts.KeptFraction(), 0.99) << floor_counts.removed << " floor points removed";
  EXPECT_EQ(binder.stats().points_removed_dynamic,
            static_cast<int64_t>(binder.removed_points().size()));
  EXPECT_GT(binder.stats().last_carve_ms, 0.0);
}

TEST(CloudBinderDynamicTest, PersonWalkingAcrossLeavesNoTrail) {
  const Box wall{{4.0, -3.0, 0.0}, {4.1, 3.0, 2.5}};
  const Box floor{{-1.0, -3.0, -0.1}, {4.0, 3.0, 0.0}};
  CloudBinder binder{RayCarvingOptions()};
  binder.SetSubmapPose(0, Rigid3d::Identity());
  std::mt19937 rng(2);
  const Rigid3d T_map_camera = CameraPose({0.0, 0.0, 1.0}, 0.0);
  // Walks from y = -1.2 to y = 1.2 at x = 2.5 in 0.15 m steps, then the scene is empty.
  const Box trail{{2.5, -1.5, 0.02}, {2.8, 1.5, 1.7}};
  for (int step = 0; step <= 16; ++step) {
    const double y = -1.2 + 0.15 * step;
    const Box person{{2.5, y - 0.2, 0.0}, {2.8, y + 0.2, 1.7}};
    binder.AddCloud(0, T_map_camera, Render({wall, floor, person}, T_map_camera, &rng));
  }
  for (int i = 0; i < 3; ++i) {
    binder.AddCloud(0, T_map_camera, Render({wall, floor}, T_map_camera, &rng));
  }
  const Kept trail_counts = CountIn(binder, trail, 0.0);

  const Kept wall_counts = CountIn(binder, wall, 0.03);
  const Kept floor_counts = CountIn(binder, floor, 0.02);
  Report("trail", trail_counts);
  Report("wall", wall_counts);
  Report("floor", floor_counts);
  std::printf("last_carve_ms=%.1f last_frame_ms=%.1f\n", binder.stats().last_carve_ms,
              binder.stats().last_frame_ms);
  EXPECT_GE(1.0 - trail_counts.KeptFraction(), 0.95) << trail_counts.kept << " trail points left";
  EXPECT_GE(wall_counts.KeptFraction(), 0.99) << wall_counts.removed << " wall points removed";
  EXPECT_GE(floor_counts.KeptFraction(), 0.99) << floor_counts.removed << " floor points removed";
}

TEST(CloudBinderDynamicTest, WallSeenAtGrazingAnglesManyTimesStays) {
  // A corridor: the camera drives along it looking down its length, so both walls and the
  // floor are seen at grazing angles, each voxel from many frames.
  const Box left_wall{{-1.0, 1.0, 0.0}, {12.0, 1.1, 2.5}};
  const Box right_wall{{-1.0, -1.1, 0.0}, {12.0, -1.0, 2.5}};
  const Box floor{{-1.0, -1.0, -0.1}, {12.0, 1.0, 0.0}};
  CloudBinder binder{RayCarvingOptions()};
  std::mt19937 rng(3);
  for (int step = 0; step < 30; ++step) {
    const int submap = step / 10;
    const Rigid3d T_map_submap(
        Eigen::Vector3d(1.0 * submap, 0.05 * submap, 0.0),
        Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * submap, Eigen::Vector3d::UnitZ())));
    if (step % 10 == 0) binder.SetSubmapPose(submap, T_map_submap);
    const Rigid3d T_map_camera =
        CameraPose({0.1 * step, 0.1 * std::sin(step), 1.0}, 0.1 * std::cos(step));
    binder.AddCloud(submap, T_map_submap.inverse() * T_map_camera,
                    Render({left_wall, right_wall, floor}, T_map_camera, &rng));
  }
  for (const Box& box : {left_wall, right_wall, floor}) {
    const Kept counts = CountIn(binder, box, 0.03);
    Report("grazing surface", counts);
    EXPECT_GT(counts.kept, 1000u);
    EXPECT_GE(counts.KeptFraction(), 0.99)
        << counts.removed << " of " << counts.kept + counts.removed;
  }
}

}  // namespace
}  // namespace cloud
}  // namespace fusemap
