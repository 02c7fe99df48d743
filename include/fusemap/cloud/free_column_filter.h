#ifndef FUSEMAP_CLOUD_FREE_COLUMN_FILTER_H_
#define FUSEMAP_CLOUD_FREE_COLUMN_FILTER_H_

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/common/config_reader.h"

namespace fusemap {
namespace cloud {

// A person seen once from the side and never looked at again by the camera leaves points no
// depth ray will ever see through. The laser, with its wide field of view, usually does: after
// the person has gone, the 2D map marks their footprint free. Points standing in such free
// columns, at body height and seen in few frames, are removed. Static structure is safe: walls,
// pillars and furniture standing on the floor are occupied in the laser map; what could hang
// over free floor (a table top) is seen in many frames and kept by max_hits.
struct FreeColumnFilterOptions {
  bool enabled = true;
  double min_z_m = 0.10;  // floor points (and the floor's depth noise) stay
  double max_z_m = 2.2;
  int max_hits = 2;       // frames that saw the voxel
  double margin_m = 0.10;  // the column and this much around it must be free in the laser map

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

// Keys: enabled, min_z_m, max_z_m, max_hits, margin_m.
FreeColumnFilterOptions ParseFreeColumnFilterOptions(common::ConfigReader& reader);

// Moves the points of `cloud` (map frame, with per-point frame counts `hits`) that the filter
// removes into `removed`; `is_free(x_m, y_m)` answers for the column and its margin. Returns
// the number of points moved.
size_t RemoveInFreeColumns(const std::function<bool(double x_m, double y_m)>& is_free,
                           const FreeColumnFilterOptions& options,
                           const std::vector<uint16_t>& hits, ColorCloud* cloud,
                           ColorCloud* removed);

}  // namespace cloud
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_FREE_COLUMN_FILTER_H_
