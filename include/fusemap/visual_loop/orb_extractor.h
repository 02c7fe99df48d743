#ifndef FUSEMAP_VISUAL_LOOP_ORB_EXTRACTOR_H_
#define FUSEMAP_VISUAL_LOOP_ORB_EXTRACTOR_H_

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

namespace fusemap {
namespace visual_loop {

struct OrbOptions {
  int max_features = 1000;
  float scale_factor = 1.2f;
  int num_levels = 8;
  int fast_threshold = 20;
  // Keypoints are spread over a grid of cells (each keeps its strongest), so that a textured
  // corner of the image cannot take the whole budget and geometry stays well conditioned.
  int grid_cols = 8;
  int grid_rows = 6;
  bool IsValid(std::string* error) const;
};

// Keypoints and their 32-byte (256-bit) ORB descriptors, row i of `descriptors` for keypoint i.
struct OrbFeatures {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;  // CV_8UC1, N x 32
};

// ORB (Rublee et al. 2011) with grid-distributed keypoints on an 8-bit grey image.
class OrbExtractor {
 public:
  explicit OrbExtractor(const OrbOptions& options);
  OrbFeatures Extract(const cv::Mat& gray) const;

 private:
  // Moves keypoints found on coarse pyramid levels to where their corner is in the image.
  // OpenCV scales a level's pixel index by the level's scale, which puts them up and left of it
  // (~1.5 px at level 6 of 1.2); a place seen at different levels in two views then reads as
  // motion: ICL's 2-10 cm steps came out 1.5-2.6 mm off without this, 1.1-1.8 mm with it.
  void ToImagePixelCentres(const cv::Size& image_size, std::vector<cv::KeyPoint>* keypoints) const;

  OrbOptions options_;
  cv::Ptr<cv::ORB> orb_;
};

// 8-bit grey view of an 8-bit grey, BGR or BGRA image (a copy only when converting).
cv::Mat ToGray(const cv::Mat& image);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_ORB_EXTRACTOR_H_
