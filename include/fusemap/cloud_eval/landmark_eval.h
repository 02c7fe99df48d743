#ifndef FUSEMAP_CLOUD_EVAL_LANDMARK_EVAL_H_
#define FUSEMAP_CLOUD_EVAL_LANDMARK_EVAL_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fusemap/cloud/cloud_types.h"
#include "fusemap/sim/world.h"

namespace fusemap {
namespace cloud_eval {

// A landmark measurable in the map cloud: the axis of a pillar (circle fit of its side) or the
// centre of a box's top face. Positions are horizontal (x, y): pillars have no height mark.
struct Landmark {
  enum class Kind { kPillar, kBoxTop };
  Kind kind = Kind::kPillar;
  std::string name;  // "pillar0", "box3": index among the world's pillars or boxes
  sim::Prism prism;
};

// The world's pillars (circular prisms), in file order, then its boxes (rectangular prisms
// lower than the ceiling) whose top is at least 5 cm below `camera_height_m`, so the camera
// sees it from above.
std::vector<Landmark> MeasurableLandmarks(const sim::World& world, double camera_height_m);

struct LandmarkEstimate {
  bool found = false;
  int points = 0;
  Eigen::Vector2d xy_m = Eigen::Vector2d::Zero();
};

// Pillar: algebraic circle fit (Kasa 1976) of the points within radius + 0.15 m of the true
// axis and 0.3 m < z < 2 m. Box top: points within the footprint (+5 cm) and 4 cm of the top
// height; the centre is the mid-point of their 2nd and 98th percentiles along the box's axes.
// Not found with fewer than 30 points. The cloud must be in the world frame.
LandmarkEstimate EstimateLandmark(const Landmark& landmark, const cloud::ColorCloud& cloud_world);

struct LandmarkPairResult {
  std::string a, b;
  double true_m = 0.0;
  double measured_m = 0.0;  // NaN if a landmark was not found
  double rel_err = 0.0;     // |measured - true| / true; NaN if not found
};

// Six pairs from the chain of MeasurableLandmarks (L0-L1, L1-L2, ..., L5-L6; fewer if the world
// has fewer landmarks), distances horizontal. In data/worlds/hall.yaml: pillar0-pillar1 and
// pillar1-pillar2 (7 m each), pillar2-box0 (16.09 m), box0-box2 (11.00 m), box2-box4
// (8.43 m) and box4-box7 (9.24 m); boxes are numbered in file order, 0, 2, 4, 7 being those
// whose top is below 0.95 m.
std::vector<LandmarkPairResult> EvaluateLandmarkPairs(const sim::World& world,
                                                      const cloud::ColorCloud& cloud_world,
                                                      double camera_height_m);

// "landmark_pair_max_rel_err=… landmark_pairs_found=N/M" (NaN max if none was found).
std::string FormatLandmarkSummary(const std::vector<LandmarkPairResult>& pairs);
// "landmark_pair a=… b=… true_m=… measured_m=… rel_err=…"
std::string FormatLandmarkPair(const LandmarkPairResult& pair);

}  // namespace cloud_eval
}  // namespace fusemap

#endif  // FUSEMAP_CLOUD_EVAL_LANDMARK_EVAL_H_
