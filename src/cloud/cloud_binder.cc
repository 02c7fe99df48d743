#include "fusemap/cloud/cloud_binder.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <unordered_set>

#include "depth_carver.h"
#include "free_space_carver.h"
#include "map_block_index.h"
#include "region_stack.h"
#include "revisit_merger.h"

namespace fusemap {
namespace cloud {
namespace {

double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

bool IsFinite(const ColorPoint& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace

void CloudBinderOptions::Check(common::OptionChecker* check) const {
  check->Require(voxel_size_m >= 0.001 && voxel_size_m <= 1.0, "voxel_size_m",
                 "must be in [0.001, 1]");
  check->Require(carve_pixel_stride >= 1 && carve_pixel_stride <= 64, "carve_pixel_stride",
                 "must be in [1, 64]");
  check->Require(carve_window_cells >= 0 && carve_window_cells <= 8, "carve_window_cells",
                 "must be in [0, 8]");
  check->Require(carve_submap_window >= 0, "carve_submap_window", "must be >= 0");
  check->Require(dynamic_no_return_carve_m >= 0.0, "dynamic_no_return_carve_m", "must be >= 0");
  check->Require(dynamic_carves_per_hit > 0.0 && dynamic_carves_per_hit <= 100.0,
                 "dynamic_carves_per_hit", "must be in (0, 100]");
  check->Require(dynamic_ray_stride >= 1, "dynamic_ray_stride", "must be >= 1");
  check->Require(dynamic_margin_voxels >= 0, "dynamic_margin_voxels", "must be >= 0");
  check->Require(dynamic_margin_range_fraction >= 0.0 && dynamic_margin_range_fraction < 0.5,
                 "dynamic_margin_range_fraction", "must be in [0, 0.5)");
  check->Require(dynamic_max_ray_length_m > 0.0, "dynamic_max_ray_length_m", "must be > 0");
  check->Require(regions_with_merge_index >= 1, "regions_with_merge_index", "must be >= 1");
  check->Require(merge_min_hits_beyond_window >= 1, "merge_min_hits_beyond_window",
                 "must be >= 1");
  check->Require(index_block_voxels >= 1 && index_block_voxels <= 64, "index_block_voxels",
                 "must be in [1, 64]");
}

bool CloudBinderOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

CloudBinderOptions ParseCloudBinderOptions(common::ConfigReader& reader) {
  CloudBinderOptions options;
  reader.Get("voxel_size_m", &options.voxel_size_m);
  reader.Get("remove_dynamic", &options.remove_dynamic);
  reader.Get("ray_carving", &options.ray_carving);
  reader.Get("carve_pixel_stride", &options.carve_pixel_stride);
  reader.Get("carve_window_cells", &options.carve_window_cells);
  reader.Get("carve_submap_window", &options.carve_submap_window);
  reader.Get("dynamic_no_return_carve_m", &options.dynamic_no_return_carve_m);
  reader.Get("dynamic_carves_per_hit", &options.dynamic_carves_per_hit);
  reader.Get("dynamic_ray_stride", &options.dynamic_ray_stride);
  reader.Get("dynamic_margin_voxels", &options.dynamic_margin_voxels);
  reader.Get("dynamic_margin_range_fraction", &options.dynamic_margin_range_fraction);
  reader.Get("dynamic_max_ray_length_m", &options.dynamic_max_ray_length_m);
  reader.Get("index_block_voxels", &options.index_block_voxels);
  reader.Get("regions_with_merge_index", &options.regions_with_merge_index);
  reader.Get("merge_revisits", &options.merge_revisits);
  reader.Get("merge_min_hits_beyond_window", &options.merge_min_hits_beyond_window);
  reader.CheckOptions(options);
  return options;
}

CloudBinder::CloudBinder(const CloudBinderOptions& options)
    : options_(options),
      index_(new MapBlockIndex(options.voxel_size_m, options.index_block_voxels)),
      removed_points_(new ColorCloud) {
  std::string error;
  assert(options.IsValid(&error));
  FreeSpaceCarverOptions carver_options;
  carver_options.voxel_size_m = options.voxel_size_m;
  carver_options.ray_stride = options.dynamic_ray_stride;
  carver_options.margin_voxels = options.dynamic_margin_voxels;
  carver_options.margin_range_fraction = options.dynamic_margin_range_fraction;
  carver_options.max_ray_length_m = options.dynamic_max_ray_length_m;
  carver_.reset(new FreeSpaceCarver(carver_options));
  DepthCarverOptions depth_options;
  depth_options.pixel_stride = options.carve_pixel_stride;
  depth_options.window_cells = options.carve_window_cells;
  depth_options.max_range_m = options.dynamic_max_ray_length_m;
  depth_options.margin_m = options.dynamic_margin_voxels * options.voxel_size_m;
  depth_options.margin_range_fraction = options.dynamic_margin_range_fraction;
  depth_options.no_return_carve_m = options.dynamic_no_return_carve_m;
  depth_carver_.reset(new DepthCarver(depth_options));
}

CloudBinder::~CloudBinder() = default;

RegionStack& CloudBinder::GetOrCreateRegion(int submap_id) {
  auto it = regions_.find(submap_id);
  if (it != regions_.end()) return *it->second;
  auto pose = T_map_submaps_.find(submap_id);
  const common::Rigid3d T_map_submap =
      pose == T_map_submaps_.end() ? common::Rigid3d::Identity() : pose->second;
  auto& region = regions_[submap_id];
  region.reset(
      new RegionStack(options_.voxel_size_m, T_map_submap, options_.dynamic_carves_per_hit));
  stats_.regions = regions_.size();
  return *region;
}

size_t CloudBinder::Repose(int submap_id, const common::Rigid3d& T_map_submap) {
  T_map_submaps_[submap_id] = T_map_submap;
  auto it = regions_.find(submap_id);
  if (it == regions_.end()) return 0;
  RegionStack& region = *it->second;
  const size_t rebuilt = region.SetPose(T_map_submap);
  if (UsesIndex()) {
    index_->RemoveRegion(submap_id);
    const auto& voxels = region.voxels();
    for (uint32_t slot = 0; slot < voxels.size(); ++slot) {
      if (voxels[slot].alive()) index_->Add(submap_id, slot, region.CenterInMap(slot));
    }
  }
  return rebuilt;
}

void CloudBinder::SetSubmapPose(int submap_id, const common::Rigid3d& T_map_submap) {
  OnSubmapsMoved({{submap_id, T_map_submap}});
}

void CloudBinder::OnSubmapsMoved(const std::vector<std::pair<int, common::Rigid3d>>& moved) {
  const auto start = std::chrono::steady_clock::now();
  size_t points = 0;
  size_t regions = 0;
  for (const auto& submap : moved) {
    const size_t rebuilt = Repose(submap.first, submap.second);
    points += rebuilt;
    if (regions_.count(submap.first) != 0) ++regions;
  }
  stats_.last_update_regions = regions;
  stats_.last_update_points = points;
  stats_.rebuilt_points_total += static_cast<int64_t>(points);
  stats_.last_update_ms = MillisecondsSince(start);
}

void CloudBinder::IndexSlots(int submap_id, const RegionStack& region,
                             const std::vector<uint32_t>& slots) {
  for (const uint32_t slot : slots) index_->Add(submap_id, slot, region.CenterInMap(slot));
}

void CloudBinder::CarveFreeSpace(const common::Rigid3d& T_map_camera,
                                 const ColorCloud& points_camera, int frame_index) {
  const Eigen::Matrix3f R = T_map_camera.rotation().toRotationMatrix().cast<float>();
  const Eigen::Vector3f t = T_map_camera.translation().cast<float>();
  std::vector<Eigen::Vector3f> points_map;
  points_map.reserve(points_camera.size());
  for (const ColorPoint& p : points_camera.points) {
    if (IsFinite(p)) points_map.push_back(R * p.getVector3fMap() + t);
  }
  const std::unordered_set<VoxelKey> carved =
      carver_->CarvedVoxels(t, points_map, *index_, frame_index);
  if (carved.empty()) return;
  std::unordered_set<VoxelKey> blocks;
  for (const VoxelKey key : carved) blocks.insert(index_->BlockKey(UnpackVoxelKey(key)));

  const float inv_voxel_size = index_->inv_voxel_size();
  std::vector<RegionVoxelRef> seen_through;
  int cached_id = 0;
  RegionStack* cached_region = nullptr;
  for (const VoxelKey block : blocks) {
    const std::vector<RegionVoxelRef>* refs = index_->Find(block);
    if (refs == nullptr) continue;
    for (const RegionVoxelRef& ref : *refs) {
      if (cached_region == nullptr || ref.region != cached_id) {
        cached_id = ref.region;
        cached_region = regions_.at(ref.region).get();
      }
      if (!cached_region->voxels()[ref.slot].alive()) continue;
      if (carved.count(KeyOf(cached_region->CenterInMap(ref.slot), inv_voxel_size)) == 0) continue;
      seen_through.push_back(ref);
    }
  }
  ApplyCarves(seen_through, frame_index);
}

void CloudBinder::ApplyCarves(const std::vector<RegionVoxelRef>& carved, int frame_index) {
  std::vector<std::pair<int, uint32_t>> to_remove;
  int cached_id = 0;
  RegionStack* cached_region = nullptr;
  for (const RegionVoxelRef& ref : carved) {
    if (cached_region == nullptr || ref.region != cached_id) {
      cached_id = ref.region;
      cached_region = regions_.at(ref.region).get();
    }
    if (cached_region->Carve(ref.slot, frame_index)) to_remove.emplace_back(ref.region, ref.slot);
  }
  // Removal after the scan: the index entries being iterated stay untouched meanwhile.
  for (const auto& victim : to_remove) {
    removed_points_->push_back(regions_.at(victim.first)->Remove(victim.second));
  }
  stats_.points_removed_dynamic += static_cast<int64_t>(to_remove.size());
  stats_.points_stored -= to_remove.size();
}

void CloudBinder::CarveWithDepth(int submap_id, const common::Rigid3d& T_submap_depth,
                                 const sensor::PinholeIntrinsics& intrinsics,
                                 const std::vector<uint16_t>& depth_mm) {
  if (!options_.remove_dynamic || options_.ray_carving) return;
  const auto start = std::chrono::steady_clock::now();
  const int frame_index = next_frame_index_++;
  ++stats_.carve_frames;
  auto pose = T_map_submaps_.find(submap_id);
  const common::Rigid3d T_map_submap =
      pose == T_map_submaps_.end() ? common::Rigid3d::Identity() : pose->second;
  const common::Rigid3d T_depth_map = (T_map_submap * T_submap_depth).inverse();
  const Eigen::Matrix3f R = T_depth_map.rotation().toRotationMatrix().cast<float>();
  const Eigen::Vector3f t = T_depth_map.translation().cast<float>();
  depth_carver_->SetImage(intrinsics, depth_mm);
  const DepthCarverOptions& depth_options = depth_carver_->options();
  const float block_m = static_cast<float>(options_.voxel_size_m * index_->block_voxels());
  const float block_radius_m = 0.5f * std::sqrt(3.f) * block_m;
  const float far_m = static_cast<float>(
      std::max(depth_options.max_range_m, depth_options.no_return_carve_m));
  std::vector<RegionVoxelRef> seen_through;
  int cached_id = 0;
  const RegionStack* cached_region = nullptr;
  for (const auto& block : index_->blocks()) {
    // Cull whole blocks against the frustum (sphere test) before looking at their voxels.
    const Eigen::Vector3f center_map =
        (UnpackVoxelKey(block.first).cast<float>() + Eigen::Vector3f::Constant(0.5f)) * block_m;
    const Eigen::Vector3f center_depth = R * center_map + t;
    if (center_depth.z() < -block_radius_m || center_depth.z() > far_m + block_radius_m) continue;
    bool outside = false;
    for (const Eigen::Vector3f& normal : depth_carver_->side_normals()) {
      outside = outside || normal.dot(center_depth) < -block_radius_m;
    }
    if (outside) continue;
    for (const RegionVoxelRef& ref : block.second) {
      if (std::abs(ref.region - submap_id) > options_.carve_submap_window) continue;
      if (cached_region == nullptr || ref.region != cached_id) {
        cached_id = ref.region;
        cached_region = regions_.at(ref.region).get();
      }
      if (!cached_region->voxels()[ref.slot].alive()) continue;
      // The voxel's mean lies on the observed surface; its centre may sit half a voxel in
      // front of it, which at grazing angles is many centimetres of depth.
      const Eigen::Vector3f mean_map = cached_region->map_cloud()[ref.slot].getVector3fMap();
      if (depth_carver_->SeesThrough(R * mean_map + t)) {
        seen_through.push_back(ref);
      }
    }
  }
  ApplyCarves(seen_through, frame_index);
  stats_.last_depth_carve_ms = MillisecondsSince(start);
}

void CloudBinder::AddCloud(int submap_id, const common::Rigid3d& T_submap_camera,
                           const CameraCloud& cloud) {
  assert(cloud.points_camera != nullptr);
  const auto start = std::chrono::steady_clock::now();
  const int frame_index = next_frame_index_++;
  ++stats_.frames;
  RegionStack& region = GetOrCreateRegion(submap_id);
  const common::Rigid3d T_map_camera = region.T_map_submap() * T_submap_camera;
  if (options_.remove_dynamic && options_.ray_carving) {
    const auto carve_start = std::chrono::steady_clock::now();
    CarveFreeSpace(T_map_camera, *cloud.points_camera, frame_index);
    stats_.last_carve_ms = MillisecondsSince(carve_start);
  }
  const ColorCloud* to_insert = cloud.points_camera.get();
  ColorCloud::Ptr not_merged;
  if (options_.merge_revisits) {
    const auto merge_start = std::chrono::steady_clock::now();
    RevisitMergeOptions merge_options;
    merge_options.carve_window = options_.carve_submap_window;
    merge_options.min_hits_beyond_window = options_.merge_min_hits_beyond_window;
    not_merged = MergeRevisits(*cloud.points_camera, T_map_camera, submap_id, frame_index,
                               merge_options, *index_, &regions_,
                               &stats_.points_merged_into_other_regions);
    to_insert = not_merged.get();
    stats_.last_merge_ms = MillisecondsSince(merge_start);
  }
  const size_t alive_before = region.num_alive();
  std::vector<uint32_t> new_slots;
  region.Insert(*to_insert, T_submap_camera, frame_index, &new_slots);
  if (UsesIndex()) IndexSlots(submap_id, region, new_slots);
  for (const ColorPoint& p : cloud.points_camera->points) {
    if (IsFinite(p)) ++stats_.points_in;
  }
  stats_.points_stored += region.num_alive() - alive_before;
  auto recent = std::find(recent_regions_.begin(), recent_regions_.end(), submap_id);
  if (recent != recent_regions_.end()) recent_regions_.erase(recent);
  recent_regions_.push_back(submap_id);
  if (static_cast<int>(recent_regions_.size()) > options_.regions_with_merge_index) {
    regions_.at(recent_regions_.front())->ReleaseKeyIndex();
    recent_regions_.erase(recent_regions_.begin());
  }
  stats_.last_frame_ms = MillisecondsSince(start);
}

ColorCloud::Ptr CloudBinder::GlobalCloud(std::vector<uint16_t>* hits) const {
  ColorCloud::Ptr cloud(new ColorCloud);
  cloud->reserve(stats_.points_stored);
  if (hits != nullptr) hits->clear();
  for (const auto& region : regions_) {
    const auto& points = region.second->map_cloud().points;
    const auto& voxels = region.second->voxels();
    for (size_t slot = 0; slot < points.size(); ++slot) {
      if (!IsFinite(points[slot])) continue;
      cloud->push_back(points[slot]);
      if (hits != nullptr) hits->push_back(voxels[slot].hits);
    }
  }
  return cloud;
}

ColorCloud::Ptr CloudBinder::RegionCloud(int submap_id) const {
  ColorCloud::Ptr cloud(new ColorCloud);
  auto it = regions_.find(submap_id);
  if (it == regions_.end()) return cloud;
  cloud->reserve(it->second->num_alive());
  for (const ColorPoint& p : it->second->map_cloud().points) {
    if (IsFinite(p)) cloud->push_back(p);
  }
  return cloud;
}

std::vector<int> CloudBinder::SubmapIds() const {
  std::vector<int> ids;
  for (const auto& region : regions_) ids.push_back(region.first);
  return ids;
}

size_t CloudBinder::MemoryBytes() const {
  size_t bytes = sizeof(*this) + index_->MemoryBytes() +
                 removed_points_->points.capacity() * sizeof(ColorPoint);
  for (const auto& region : regions_) bytes += region.second->MemoryBytes();
  return bytes;
}

}  // namespace cloud
}  // namespace fusemap
