#ifndef FUSEMAP_IO_CLOUD_IMAGE_H_
#define FUSEMAP_IO_CLOUD_IMAGE_H_

#include <string>

#include "fusemap/cloud/cloud_types.h"

namespace fusemap {
namespace io {

// An oblique bird's-eye view of a coloured cloud, for people to look at the 3D map in a
// README or a report without a viewer.
struct CloudImageOptions {
  int width_px = 1600;
  double azimuth_deg = -60.0;   // direction the viewer looks from, about the map's z axis
  double elevation_deg = 55.0;  // above the horizon; 90 is straight down
  // Points above this height are left out: an indoor ceiling hides everything below it.
  double clip_above_m = 2.4;
  int splat_px = 2;  // points are drawn as squares of this edge, nearest wins
};

// Renders with an orthographic camera fitted to the cloud's extent, a depth buffer so near
// surfaces hide far ones, and a dark background. Returns false with a message naming the path
// if the cloud is empty or the file cannot be written.
bool WriteCloudPng(const cloud::ColorCloud& cloud, const CloudImageOptions& options,
                   const std::string& path, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_CLOUD_IMAGE_H_
