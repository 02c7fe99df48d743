#include "fusemap/cloud_eval/cloud_eval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "fusemap/sim/surface_distance.h"

namespace fusemap {
namespace cloud_eval {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Median(std::vector<double>* values) {
  if (values->empty()) return kNaN;
  const size_t mid = values->size() / 2;
  std::nth_element(values->begin(), values->begin() + mid, values->end());
  const double upper = (*values)[mid];
  if (values->size() % 2 == 1) return upper;
  const double lower = *std::max_element(values->begin(), values->begin() + mid);
  return 0.5 * (lower + upper);
}

double Fraction(int64_t part, int64_t total) {
  return total > 0 ? static_cast<double>(part) / static_cast<double>(total) : kNaN;
}

}  // namespace

bool IsDynamicPoint(const sim::World& world, const Eigen::Vector3d& p_world,
                    double static_tolerance_m, double* static_distance_m) {
  const double to_static_m = sim::DistanceToStaticSurface(world, p_world);
  if (static_distance_m != nullptr) *static_distance_m = to_static_m;
  if (to_static_m <= static_tolerance_m) return false;
  return sim::DistanceToPeoplePaths(world, p_world) < to_static_m;
}

CloudEvalResult EvaluateCloud(const sim::World& world, const cloud::ColorCloud& kept,
                              const cloud::ColorCloud* removed, double static_tolerance_m) {
  CloudEvalResult result;
  std::vector<double> static_distances_m;
  static_distances_m.reserve(kept.size());
  for (const cloud::ColorPoint& p : kept) {
    double to_static_m = 0.0;
    if (IsDynamicPoint(world, Eigen::Vector3d(p.x, p.y, p.z), static_tolerance_m, &to_static_m)) {
      ++result.kept_dynamic;
    } else {
      ++result.kept_static;
      static_distances_m.push_back(to_static_m);
    }
  }
  result.median_surface_dist_m = Median(&static_distances_m);
  result.have_removed = removed != nullptr;
  if (removed == nullptr) {
    result.dynamic_removed_frac = kNaN;
    result.static_kept_frac = kNaN;
    return result;
  }
  for (const cloud::ColorPoint& p : *removed) {
    if (IsDynamicPoint(world, Eigen::Vector3d(p.x, p.y, p.z), static_tolerance_m, nullptr)) {
      ++result.removed_dynamic;
    } else {
      ++result.removed_static;
    }
  }
  result.dynamic_removed_frac =
      Fraction(result.removed_dynamic, result.removed_dynamic + result.kept_dynamic);
  result.static_kept_frac = Fraction(result.kept_static, result.kept_static + result.removed_static);
  return result;
}

std::string FormatCloudEvalLine(const CloudEvalResult& result) {
  char line[160];
  std::snprintf(line, sizeof(line),
                "median_surface_dist_m=%.5f dynamic_removed_frac=%.5f static_kept_frac=%.5f",
                result.median_surface_dist_m, result.dynamic_removed_frac, result.static_kept_frac);
  return line;
}

}  // namespace cloud_eval
}  // namespace fusemap
