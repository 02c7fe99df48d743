#include "fusemap/cloud/free_column_filter.h"

#include <cassert>

namespace fusemap {
namespace cloud {

void FreeColumnFilterOptions::Check(common::OptionChecker* check) const {
  check->Require(min_z_m < max_z_m, "min_z_m", "must be below max_z_m");
  check->Require(max_hits >= 0, "max_hits", "must be >= 0");
  check->Require(margin_m >= 0.0 && margin_m <= 2.0, "margin_m", "must be in [0, 2]");
}

bool FreeColumnFilterOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

FreeColumnFilterOptions ParseFreeColumnFilterOptions(common::ConfigReader& reader) {
  FreeColumnFilterOptions options;
  reader.Get("enabled", &options.enabled);
  reader.Get("min_z_m", &options.min_z_m);
  reader.Get("max_z_m", &options.max_z_m);
  reader.Get("max_hits", &options.max_hits);
  reader.Get("margin_m", &options.margin_m);
  reader.CheckOptions(options);
  return options;
}

size_t RemoveInFreeColumns(const std::function<bool(double x_m, double y_m)>& is_free,
                           const FreeColumnFilterOptions& options,
                           const std::vector<uint16_t>& hits, ColorCloud* cloud,
                           ColorCloud* removed) {
  assert(hits.size() == cloud->size());
  if (!options.enabled) return 0;
  ColorCloud kept;
  kept.reserve(cloud->size());
  size_t moved = 0;
  for (size_t i = 0; i < cloud->size(); ++i) {
    const ColorPoint& p = (*cloud)[i];
    if (p.z >= options.min_z_m && p.z <= options.max_z_m && hits[i] <= options.max_hits &&
        is_free(p.x, p.y)) {
      removed->push_back(p);
      ++moved;
    } else {
      kept.push_back(p);
    }
  }
  cloud->swap(kept);
  return moved;
}

}  // namespace cloud
}  // namespace fusemap
