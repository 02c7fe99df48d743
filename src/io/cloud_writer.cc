#include "fusemap/io/cloud_writer.h"

#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>
#include <pcl/conversions.h>
#include <pcl/exceptions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/conversions.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "ply_header.h"
#include "write_all.h"

namespace fusemap {
namespace io {
namespace {

bool Fail(std::string* error, const std::string& message) {
  if (error != nullptr) *error = message;
  return false;
}

bool CanRead(const std::string& path, std::string* error) {
  std::ifstream probe(path, std::ios::binary);
  if (!probe) return Fail(error, "cannot open " + path + ": " + std::strerror(errno));
  return true;
}

// PCL refuses to write a cloud without points, yet "nothing removed" or "nothing mapped" is a
// result: such files get the header PCL would write, with zero points.
std::string EmptyCloudHeader(const cloud::ColorCloud& cloud, bool ply) {
  pcl::PCLPointCloud2 fields;
  pcl::toPCLPointCloud2(cloud, fields);
  const Eigen::Vector4f origin = Eigen::Vector4f::Zero();
  const Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  if (ply) {
    return pcl::PLYWriter().generateHeaderBinary(fields, origin, orientation, 0,
                                                 /*use_camera=*/false);
  }
  return pcl::PCDWriter().generateHeaderBinary(fields, origin, orientation) + "DATA binary\n";
}

// Inner occupancy, pruning, then the file: .bt (writeBinary, occupancy only) or .ot (write, the
// full tree with colours). octomap dereferences the root in updateInnerOccupancy: an empty
// cloud has none, and its tree is written as it is.
template <typename Tree>
bool FinishAndWriteTree(Tree* tree, bool binary, const std::string& path, std::string* error) {
  if (tree->getRoot() != nullptr) {
    tree->updateInnerOccupancy();
    tree->prune();
  }
  std::ostringstream bytes;
  if (!(binary ? tree->writeBinary(bytes) : tree->write(bytes))) {
    return Fail(error, "failed to encode OctoMap " + path);
  }
  return WriteFileAtomically(path, bytes.str(), error);
}

}  // namespace

bool WriteCloudPly(const std::string& path, const cloud::ColorCloud& cloud, std::string* error) {
  if (cloud.empty()) return WriteFileAtomically(path, EmptyCloudHeader(cloud, true), error);
  return WriteFileAtomically(
      path,
      [&](const std::string& tmp, std::string* write_error) {
        try {
          pcl::PLYWriter writer;
          // use_camera = false: no PCL-specific camera element, so any PLY reader accepts it.
          if (writer.write(tmp, cloud, /*binary=*/true, /*use_camera=*/false) != 0) {
            return Fail(write_error, "failed to write PLY " + path);
          }
        } catch (const pcl::PCLException& e) {
          return Fail(write_error, "failed to write PLY " + path + ": " + e.what());
        }
        return true;
      },
      error);
}

bool WriteCloudPcd(const std::string& path, const cloud::ColorCloud& cloud, std::string* error) {
  if (cloud.empty()) return WriteFileAtomically(path, EmptyCloudHeader(cloud, false), error);
  return WriteFileAtomically(
      path,
      [&](const std::string& tmp, std::string* write_error) {
        try {
          if (pcl::io::savePCDFileBinary(tmp, cloud) != 0) {
            return Fail(write_error, "failed to write PCD " + path);
          }
        } catch (const pcl::PCLException& e) {
          return Fail(write_error, "failed to write PCD " + path + ": " + e.what());
        }
        return true;
      },
      error);
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
  if (!CanRead(path, error) || !CheckPlyFileSize(path, error)) return false;
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
    octomap::OcTree tree(resolution_m);
    for (const cloud::ColorPoint& p : cloud_map) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      tree.updateNode(octomap::point3d(p.x, p.y, p.z), /*occupied=*/true, /*lazy_eval=*/true);
    }
    if (!FinishAndWriteTree(&tree, /*binary=*/true, bt_path, error)) return false;
  }
  if (!ot_path.empty()) {
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
    // FinishAndWriteTree also sets inner nodes' colours to their children's average.
    if (!FinishAndWriteTree(&tree, /*binary=*/false, ot_path, error)) return false;
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
