#include "region_stack.h"

#include <cassert>
#include <limits>

namespace fusemap {
namespace cloud {
namespace {

constexpr uint16_t kMaxCount = std::numeric_limits<uint16_t>::max();

ColorPoint NanPoint() {
  ColorPoint p;
  p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
  return p;
}

}  // namespace

RegionStack::RegionStack(double voxel_size_m, const common::Rigid3d& T_map_submap,
                         double carves_per_hit)
    : voxel_size_m_(static_cast<float>(voxel_size_m)),
      inv_voxel_size_(static_cast<float>(1.0 / voxel_size_m)),
      carves_per_hit_(static_cast<float>(carves_per_hit)),
      map_cloud_(new ColorCloud) {
  assert(voxel_size_m > 0.0);
  map_cloud_->is_dense = false;
  SetPose(T_map_submap);
}

ColorPoint RegionStack::ToMapPoint(const RegionVoxel& voxel) const {
  ColorPoint p;
  p.getVector3fMap() = R_map_submap_ * voxel.mean_submap + t_map_submap_;
  p.r = static_cast<uint8_t>(voxel.mean_rgb.x() + 0.5f);
  p.g = static_cast<uint8_t>(voxel.mean_rgb.y() + 0.5f);
  p.b = static_cast<uint8_t>(voxel.mean_rgb.z() + 0.5f);
  return p;
}

void RegionStack::Insert(const ColorCloud& points_camera, const common::Rigid3d& T_submap_camera,
                         int frame_index, std::vector<uint32_t>* new_slots) {
  if (!has_key_index_) {
    slot_of_key_.reserve(num_alive_);
    for (uint32_t slot = 0; slot < voxels_.size(); ++slot) {
      if (voxels_[slot].alive()) slot_of_key_.emplace(voxels_[slot].key, slot);
    }
    has_key_index_ = true;
  }
  const Eigen::Matrix3f R = T_submap_camera.rotation().toRotationMatrix().cast<float>();
  const Eigen::Vector3f t = T_submap_camera.translation().cast<float>();
  for (const ColorPoint& point : points_camera.points) {
    if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) continue;
    const Eigen::Vector3f p_submap = R * point.getVector3fMap() + t;
    const Eigen::Vector3f rgb(point.r, point.g, point.b);
    const VoxelKey key = KeyOf(p_submap, inv_voxel_size_);
    auto inserted = slot_of_key_.emplace(key, static_cast<uint32_t>(voxels_.size()));
    if (inserted.second) {
      RegionVoxel voxel;
      voxel.key = key;
      voxel.mean_submap = p_submap;
      voxel.mean_rgb = rgb;
      voxel.num_points = 1;
      voxel.hits = 1;
      voxel.last_hit_frame = frame_index;
      voxels_.push_back(voxel);
      map_cloud_->push_back(ToMapPoint(voxel));
      ++num_alive_;
      if (new_slots != nullptr) new_slots->push_back(inserted.first->second);
      continue;
    }
    AddHit(inserted.first->second, p_submap, rgb, frame_index);
  }
  map_cloud_->width = static_cast<uint32_t>(map_cloud_->size());
  map_cloud_->height = 1;
}

void RegionStack::AddHit(uint32_t slot, const Eigen::Vector3f& p_submap, const Eigen::Vector3f& rgb,
                         int frame_index) {
  assert(slot < voxels_.size() && voxels_[slot].alive());
  RegionVoxel& voxel = voxels_[slot];
  // Running means keep float precision bounded however often a wall is re-observed.
  voxel.num_points = voxel.num_points == std::numeric_limits<uint32_t>::max()
                         ? voxel.num_points
                         : voxel.num_points + 1;
  const float w = 1.f / static_cast<float>(voxel.num_points);
  voxel.mean_submap += w * (p_submap - voxel.mean_submap);
  voxel.mean_rgb += w * (rgb - voxel.mean_rgb);
  if (voxel.last_hit_frame != frame_index) {
    voxel.last_hit_frame = frame_index;
    if (voxel.hits < kMaxCount) ++voxel.hits;
  }
  (*map_cloud_)[slot] = ToMapPoint(voxel);
}

void RegionStack::ReleaseKeyIndex() {
  std::unordered_map<VoxelKey, uint32_t>().swap(slot_of_key_);
  has_key_index_ = false;
}

size_t RegionStack::SetPose(const common::Rigid3d& T_map_submap) {
  T_map_submap_ = T_map_submap;
  R_map_submap_ = T_map_submap.rotation().toRotationMatrix().cast<float>();
  t_map_submap_ = T_map_submap.translation().cast<float>();
  size_t rebuilt = 0;
  for (size_t i = 0; i < voxels_.size(); ++i) {
    if (!voxels_[i].alive()) continue;
    (*map_cloud_)[i].getVector3fMap() = R_map_submap_ * voxels_[i].mean_submap + t_map_submap_;
    ++rebuilt;
  }
  return rebuilt;
}

bool RegionStack::Carve(uint32_t slot, int frame_index) {
  assert(slot < voxels_.size());
  RegionVoxel& voxel = voxels_[slot];
  if (!voxel.alive() || voxel.last_hit_frame == frame_index ||
      voxel.last_carve_frame == frame_index) {
    return false;
  }
  voxel.last_carve_frame = frame_index;
  if (voxel.carves < kMaxCount) ++voxel.carves;
  // Removal rule: free-space evidence must match occupancy evidence, counted in frames
  // (carves >= hits). A surface seen in many frames survives the odd ray that grazes it, while
  // a person who stood still for k frames is gone once k later frames saw through them; a
  // voxel seen in a single frame goes on its first carve. Ties remove because the carver already
  // refuses every carve near a surface the carving frame itself observed (and within a margin
  // before the ray's end), so a carve is strong evidence; waiting for carves > hits left the
  // last few positions of a walking person in the map (test: PersonWalkingAcrossLeavesNoTrail).
  // carves_per_hit > 1 balances carving with more frames than are bound (projective carving
  // uses every frame, hits count only the bound ones).
  return static_cast<float>(voxel.carves) >= carves_per_hit_ * static_cast<float>(voxel.hits);
}

ColorPoint RegionStack::Remove(uint32_t slot) {
  assert(slot < voxels_.size());
  RegionVoxel& voxel = voxels_[slot];
  assert(voxel.alive());
  const ColorPoint removed = (*map_cloud_)[slot];
  if (has_key_index_) slot_of_key_.erase(voxel.key);
  voxel.num_points = 0;
  (*map_cloud_)[slot] = NanPoint();
  --num_alive_;
  return removed;
}

Eigen::Vector3f RegionStack::CenterInMap(uint32_t slot) const {
  return R_map_submap_ * VoxelCenter(voxels_[slot].key, voxel_size_m_) + t_map_submap_;
}

size_t RegionStack::MemoryBytes() const {
  // Node-based hash map: key, value, next pointer and allocator overhead per entry, plus buckets.
  const size_t hash_bytes = slot_of_key_.size() * (sizeof(VoxelKey) + sizeof(uint32_t) + 24) +
                            slot_of_key_.bucket_count() * sizeof(void*);
  return sizeof(*this) + hash_bytes + voxels_.capacity() * sizeof(RegionVoxel) +
         map_cloud_->points.capacity() * sizeof(ColorPoint);
}

}  // namespace cloud
}  // namespace fusemap
