#include "revisit_merger.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <unordered_map>

#include "region_stack.h"

namespace fusemap {
namespace cloud {
namespace {

// A region with live voxels in the blocks the frame touches: those voxels by submap key, and
// the map-to-submap transform that puts a point into its grid.
struct Candidate {
  const RegionStack* region = nullptr;
  int32_t id = 0;
  Eigen::Matrix3f R_submap_map;
  Eigen::Vector3f t_submap_map;
  int min_hits = 1;
  std::unordered_map<VoxelKey, uint32_t> slot_of_key;
};

void AddUnique(int value, std::vector<int>* values) {
  if (std::find(values->begin(), values->end(), value) == values->end()) values->push_back(value);
}

}  // namespace

std::vector<RevisitMatch> FindRevisitedVoxels(
    const std::vector<Eigen::Vector3f>& points_map, int own_region,
    const RevisitMergeOptions& options, const MapBlockIndex& index,
    const std::map<int, std::unique_ptr<RegionStack>>& regions) {
  std::vector<RevisitMatch> matches;
  const float inv_voxel_size = index.inv_voxel_size();
  std::vector<VoxelKey> block_of_point(points_map.size());
  // Per block near the frame: candidate indices present in it. A region voxel that holds a
  // point has its centre in a map voxel within one of the point's, so the blocks of those.
  std::unordered_map<VoxelKey, std::vector<int>> present;
  Eigen::Vector3i last_lo = Eigen::Vector3i::Zero();
  Eigen::Vector3i last_hi = Eigen::Vector3i::Zero();
  for (size_t i = 0; i < points_map.size(); ++i) {
    const Eigen::Vector3i voxel = VoxelIndex(points_map[i], inv_voxel_size);
    block_of_point[i] = index.BlockKey(voxel);
    const Eigen::Vector3i lo = UnpackVoxelKey(index.BlockKey(voxel - Eigen::Vector3i::Ones()));
    const Eigen::Vector3i hi = UnpackVoxelKey(index.BlockKey(voxel + Eigen::Vector3i::Ones()));
    if (i > 0 && lo == last_lo && hi == last_hi) continue;  // consecutive points are neighbours
    last_lo = lo;
    last_hi = hi;
    for (int x = lo.x(); x <= hi.x(); ++x) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int z = lo.z(); z <= hi.z(); ++z) {
          present.try_emplace(PackVoxelKey(Eigen::Vector3i(x, y, z)));
        }
      }
    }
  }
  std::vector<Candidate> candidates;
  std::unordered_map<int, int> candidate_of_region;
  for (auto& block : present) {
    const std::vector<RegionVoxelRef>* refs = index.Find(block.first);
    if (refs == nullptr) continue;
    int last_region = own_region;
    Candidate* candidate = nullptr;
    for (const RegionVoxelRef& ref : *refs) {
      if (ref.region == own_region) continue;
      if (candidate == nullptr || ref.region != last_region) {
        last_region = ref.region;
        auto inserted =
            candidate_of_region.emplace(ref.region, static_cast<int>(candidates.size()));
        if (inserted.second) {
          candidates.emplace_back();
          Candidate& added = candidates.back();
          added.region = regions.at(ref.region).get();
          added.id = ref.region;
          added.min_hits = std::abs(ref.region - own_region) > options.carve_window
                               ? options.min_hits_beyond_window
                               : 1;
          const common::Rigid3d T_submap_map = added.region->T_map_submap().inverse();
          added.R_submap_map = T_submap_map.rotation().toRotationMatrix().cast<float>();
          added.t_submap_map = T_submap_map.translation().cast<float>();
        }
        candidate = &candidates[inserted.first->second];
        AddUnique(inserted.first->second, &block.second);
      }
      const RegionVoxel& voxel = candidate->region->voxels()[ref.slot];
      if (!voxel.alive() || voxel.hits < candidate->min_hits) continue;
      candidate->slot_of_key.emplace(candidate->region->voxels()[ref.slot].key, ref.slot);
    }
  }
  if (candidates.empty()) return matches;

  // Candidates of a point's block: those present in it or a neighbouring block.
  std::unordered_map<VoxelKey, std::vector<int>> nearby;
  auto nearby_of = [&](VoxelKey block) -> const std::vector<int>& {
    auto inserted = nearby.try_emplace(block);
    if (!inserted.second) return inserted.first->second;
    std::vector<int>& near = inserted.first->second;
    const Eigen::Vector3i center = UnpackVoxelKey(block);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = present.find(PackVoxelKey(center + Eigen::Vector3i(dx, dy, dz)));
          if (it == present.end()) continue;
          for (const int c : it->second) AddUnique(c, &near);
        }
      }
    }
    return near;
  };

  VoxelKey cached_block = 0;
  const std::vector<int>* near = nullptr;
  for (size_t i = 0; i < points_map.size(); ++i) {
    if (near == nullptr || block_of_point[i] != cached_block) {
      cached_block = block_of_point[i];
      near = &nearby_of(cached_block);
    }
    RevisitMatch best;
    int best_hits = -1;
    for (const int c : *near) {
      const Candidate& candidate = candidates[c];
      const Eigen::Vector3f p_submap =
          candidate.R_submap_map * points_map[i] + candidate.t_submap_map;
      auto it = candidate.slot_of_key.find(KeyOf(p_submap, inv_voxel_size));
      if (it == candidate.slot_of_key.end()) continue;
      const int hits = candidate.region->voxels()[it->second].hits;
      if (hits <= best_hits) continue;
      best_hits = hits;
      best.point = static_cast<uint32_t>(i);
      best.voxel = RegionVoxelRef{candidate.id, it->second};
      best.p_submap = p_submap;
    }
    if (best_hits >= 0) matches.push_back(best);
  }
  return matches;
}

ColorCloud::Ptr MergeRevisits(const ColorCloud& points_camera, const common::Rigid3d& T_map_camera,
                              int own_region, int frame_index, const RevisitMergeOptions& options,
                              const MapBlockIndex& index,
                              std::map<int, std::unique_ptr<RegionStack>>* regions,
                              int64_t* merged) {
  const Eigen::Matrix3f R = T_map_camera.rotation().toRotationMatrix().cast<float>();
  const Eigen::Vector3f t = T_map_camera.translation().cast<float>();
  std::vector<Eigen::Vector3f> points_map;
  std::vector<uint32_t> source;  // index in points_camera of each of points_map
  for (uint32_t i = 0; i < points_camera.size(); ++i) {
    const ColorPoint& p = points_camera[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    points_map.push_back(R * p.getVector3fMap() + t);
    source.push_back(i);
  }
  const std::vector<RevisitMatch> matches =
      FindRevisitedVoxels(points_map, own_region, options, index, *regions);
  ColorCloud::Ptr rest(new ColorCloud);
  rest->reserve(points_map.size() - matches.size());
  size_t next = 0;
  for (uint32_t i = 0; i < points_map.size(); ++i) {
    const ColorPoint& p = points_camera[source[i]];
    if (next == matches.size() || matches[next].point != i) {
      rest->push_back(p);
      continue;
    }
    const RevisitMatch& match = matches[next++];
    regions->at(match.voxel.region)
        ->AddHit(match.voxel.slot, match.p_submap, Eigen::Vector3f(p.r, p.g, p.b), frame_index);
  }
  *merged += static_cast<int64_t>(matches.size());
  return rest;
}

}  // namespace cloud
}  // namespace fusemap
