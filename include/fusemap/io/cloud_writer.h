#ifndef FUSEMAP_IO_CLOUD_WRITER_H_
#define FUSEMAP_IO_CLOUD_WRITER_H_

#include <string>

#include "fusemap/cloud/cloud_types.h"

namespace fusemap {
namespace io {

// Disk formats of the coloured map. Every function returns false and fills *error, naming the
// path, when the file cannot be opened, written or parsed.

// Binary little-endian PLY with float x, y, z and uchar red, green, blue per vertex.
bool WriteCloudPly(const std::string& path, const cloud::ColorCloud& cloud, std::string* error);
// Binary PCD (fields x y z rgb).
bool WriteCloudPcd(const std::string& path, const cloud::ColorCloud& cloud, std::string* error);

// Read what the writers above (or other tools) wrote. A file without colour reads as black.
bool ReadCloudPly(const std::string& path, cloud::ColorCloud* cloud, std::string* error);
bool ReadCloudPcd(const std::string& path, cloud::ColorCloud* cloud, std::string* error);

// OctoMap export at resolution_m: an octomap::OcTree (.bt, writeBinary: occupied or free bits)
// and an octomap::ColorOcTree (.ot, full format) with each voxel's colour the average of its
// points. Every point marks its voxel occupied; no rays are cast, so free space stays unknown
// (the cloud has already been cleared of dynamic points). Either path may be empty to skip it.
bool WriteOctoMaps(const cloud::ColorCloud& cloud_map, double resolution_m,
                   const std::string& bt_path, const std::string& ot_path, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_CLOUD_WRITER_H_
