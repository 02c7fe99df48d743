#include "fusemap/io/cloud_writer.h"

#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>
#include <pcl/conversions.h>
#include <pcl/exceptions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <fstream>
#include <unordered_map>

namespace fusemap {
namespace io {
namespace {

bool Fail(std::string* error, const std::string& message) {
  if (error != nullptr) *error = message;
  return false;
}

// PCL reports an unopenable file on its console (or by throwing); probing first gives the
// caller a message with the path and the reason.
bool CanWrite(const std::string& path, std::string* error) {
  std::ofstream probe(path, std::ios::binary | std::ios::trunc);
  if (!probe) return Fail(error, "cannot open " + path + " for writing: " + std::strerror(errno));
  return true;
}

bool CanRead(const std::string& path, std::string* error) {
  std::ifstream probe(path, std::ios::binary);
  if (!probe) return Fail(error, "cannot open " + path + ": " + std::strerror(errno));
  return true;
}

}  // namespace

bool WriteCloudPly(const std::string& path, const cloud::ColorCloud& cloud, std::string* error) {
  if (!CanWrite(path, error)) return false;
  try {
    pcl::PLYWriter writer;
    // use_camera = false: no PCL-specific camera element, so any PLY reader accepts the file.
    if (writer.write(path, cloud, /*binary=*/true, /*use_camera=*/false) != 0) {
      return Fail(error, "failed to write PLY " + path);
    }
  } catch (const pcl::PCLException& e) {
    return Fail(error, "failed to write PLY " + path + ": " + e.what());
  }
  return true;
}

bool WriteCloudPcd(const std::string& path, const cloud::ColorCloud& cloud, std::string* error) {
  if (!CanWrite(path, error)) return false;
  try {
    if (pcl::io::savePCDFileBinary(path, cloud) != 0) {
      return Fail(error, "failed to write PCD " + path);
    }
  } catch (const pcl::PCLException& e) {
    return Fail(error, "failed to write PCD " + path + ": " + e.what());
  }
  return true;
}

namespace {

// PCL 1.13's fromPCLPointCloud2 (which loadPLYFile/loadPCDFile into a typed cloud call) takes
// &cloud[0] of the resized cloud even when it has no points: undefined behaviour, UBSan's
// "reference binding to null pointer" at conversions.h:178 on reading an empty file.
void FromBlob(const pcl::PCLPointCloud2& blob, cloud::ColorCloud* cloud) {
  if (static_cast<uint64_t>(blob.width) * blob.height == 0) {
    cloud->clear();
    return;
  }
  pcl::fromPCLPointCloud2(blob, *cloud);
}

}  // namespace

bool ReadCloudPly(const std::string& path, cloud::ColorCloud* cloud, std::string* error) {
  if (!CanRead(path, error)) return false;
  try {
    pcl::PCLPointCloud2 blob;
    if (pcl::io::loadPLYFile(path, blob) != 0) {
      return Fail(error, path + ": not a readable PLY point cloud");
    }
    FromBlob(blob, cloud);
  } catch (const pcl::PCLException& e) {
    return Fail(error, path + ": " + e.what());
  }
  return true;
}

bool ReadCloudPcd(const std::string& path, cloud::ColorCloud* cloud, std::string* error) {
  if (!CanRead(path, error)) return false;
  try {
    pcl::PCLPointCloud2 blob;
    if (pcl::io::loadPCDFile(path, blob) != 0) {
      return Fail(error, path + ": not a readable PCD point cloud");
    }
    FromBlob(blob, cloud);
  } catch (const pcl::PCLException& e) {
    return Fail(error, path + ": " + e.what());
  }
  return true;
}

bool WriteOctoMaps(const cloud::ColorCloud& cloud_map, double resolution_m,
                   const std::string& bt_path, const std::string& ot_path, std::string* error) {
  if (!(resolution_m > 0.0)) return Fail(error, "octomap resolution must be > 0");
  if (!bt_path.empty()) {
    if (!CanWrite(bt_path, error)) return false;
    octomap::OcTree tree(resolution_m);
    for (const cloud::ColorPoint& p : cloud_map) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      tree.updateNode(octomap::point3d(p.x, p.y, p.z), /*occupied=*/true, /*lazy_eval=*/true);
    }
    tree.updateInnerOccupancy();
    tree.prune();
    if (!tree.writeBinary(bt_path)) return Fail(error, "failed to write OctoMap " + bt_path);
  }
  if (!ot_path.empty()) {
    if (!CanWrite(ot_path, error)) return false;
    octomap::ColorOcTree tree(resolution_m);
    // The true mean colour per voxel (ColorOcTree::averageNodeColor halves the weight of all
    // earlier points at each call, so the last points would dominate).
    struct ColorSum {
      uint64_t r = 0, g = 0, b = 0, n = 0;
    };
    std::unordered_map<octomap::OcTreeKey, ColorSum, octomap::OcTreeKey::KeyHash> sums;
    for (const cloud::ColorPoint& p : cloud_map) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      octomap::OcTreeKey key;
      if (!tree.coordToKeyChecked(octomap::point3d(p.x, p.y, p.z), key)) continue;
      tree.updateNode(key, /*occupied=*/true, /*lazy_eval=*/true);
      ColorSum& sum = sums[key];
      sum.r += p.r;
      sum.g += p.g;
      sum.b += p.b;
      ++sum.n;
    }
    for (const auto& [key, sum] : sums) {
      tree.setNodeColor(key, static_cast<uint8_t>((sum.r + sum.n / 2) / sum.n),
                        static_cast<uint8_t>((sum.g + sum.n / 2) / sum.n),
                        static_cast<uint8_t>((sum.b + sum.n / 2) / sum.n));
    }
    // Also sets inner nodes' colours to their children's average.
    tree.updateInnerOccupancy();
    tree.prune();
    if (!tree.write(ot_path)) return Fail(error, "failed to write OctoMap " + ot_path);
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
