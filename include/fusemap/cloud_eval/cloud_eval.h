#ifndef FUSEMAP_CLOUD_EVAL_CLOUD_EVAL_H_
#define FUSEMAP_CLOUD_EVAL_CLOUD_EVAL_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/sim/world.h"

namespace fusemap {
namespace cloud_eval {

// A map point lies either on static structure or on where a person walked. "Dynamic": closer
// to the volume swept by a person than to any static surface, and farther than the tolerance
// from every static surface (so the floor under a person's feet stays static).
bool IsDynamicPoint(const sim::World& world, const Eigen::Vector3d& p_world,
                    double static_tolerance_m, double* static_distance_m);

struct CloudEvalResult {
  int64_t kept_static = 0;
  int64_t kept_dynamic = 0;
  int64_t removed_static = 0;
  int64_t removed_dynamic = 0;
  bool have_removed = false;  // Whether the removed cloud was known.
  double median_surface_dist_m = 0.0;  // Over kept static points; NaN if there are none.
  double dynamic_removed_frac = 0.0;   // removed_dynamic / all dynamic; NaN if unknown.
  double static_kept_frac = 0.0;       // kept_static / all static; NaN if unknown.
};

// Scores a map (`kept`, world frame) and the points its dynamic removal took out (`removed`;
// null when unknown) against the simulator's world.
CloudEvalResult EvaluateCloud(const sim::World& world, const cloud::ColorCloud& kept,
                              const cloud::ColorCloud* removed, double static_tolerance_m);

// "median_surface_dist_m=… dynamic_removed_frac=… static_kept_frac=…" (no newline).
std::string FormatCloudEvalLine(const CloudEvalResult& result);

}  // namespace cloud_eval
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_EVAL_CLOUD_EVAL_H_
