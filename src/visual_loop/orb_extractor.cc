#include "fusemap/visual_loop/orb_extractor.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace fusemap {
namespace visual_loop {

bool OrbOptions::IsValid(std::string* error) const {
  if (max_features < 10) {
    *error = "max_features must be at least 10";
    return false;
  }
  if (scale_factor <= 1.0f || num_levels < 1 || fast_threshold < 1) {
    *error = "scale_factor must exceed 1, num_levels and fast_threshold be positive";
    return false;
  }
  if (grid_cols < 1 || grid_rows < 1) {
    *error = "grid_cols and grid_rows must be positive";
    return false;
  }
  return true;
}

OrbExtractor::OrbExtractor(const OrbOptions& options) : options_(options) {
  std::string error;
  assert(options_.IsValid(&error));
  // Detect twice the budget so that sparse cells can still be filled from their own corners;
  // an edge threshold of 19 (as ORB-SLAM) lets the outer cells keep corners too.
  orb_ = cv::ORB::create(2 * options_.max_features, options_.scale_factor, options_.num_levels,
                         19, 0, 2, cv::ORB::HARRIS_SCORE, 31, options_.fast_threshold);
}

OrbFeatures OrbExtractor::Extract(const cv::Mat& gray) const {
  assert(gray.type() == CV_8UC1);
  std::vector<cv::KeyPoint> detected;
  orb_->detect(gray, detected);

  const int num_cells = options_.grid_cols * options_.grid_rows;
  std::vector<std::vector<int>> cells(num_cells);
  for (int i = 0; i < static_cast<int>(detected.size()); ++i) {
    const int cx = std::clamp(static_cast<int>(detected[i].pt.x * options_.grid_cols / gray.cols),
                              0, options_.grid_cols - 1);
    const int cy = std::clamp(static_cast<int>(detected[i].pt.y * options_.grid_rows / gray.rows),
                              0, options_.grid_rows - 1);
    cells[cy * options_.grid_cols + cx].push_back(i);
  }
  const auto stronger = [&](int a, int b) { return detected[a].response > detected[b].response; };
  const int per_cell = (options_.max_features + num_cells - 1) / num_cells;
  std::vector<int> kept;
  std::vector<int> spare;
  for (auto& cell : cells) {
    std::sort(cell.begin(), cell.end(), stronger);
    for (int j = 0; j < static_cast<int>(cell.size()); ++j) {
      (j < per_cell ? kept : spare).push_back(cell[j]);
    }
  }
  // Cells without texture leave budget over: give it to the strongest of the rest.
  if (static_cast<int>(kept.size()) > options_.max_features) {
    std::sort(kept.begin(), kept.end(), stronger);
    kept.resize(options_.max_features);
  } else {
    std::sort(spare.begin(), spare.end(), stronger);
    const int missing = options_.max_features - static_cast<int>(kept.size());
    kept.insert(kept.end(), spare.begin(),
                spare.begin() + std::min<int>(missing, static_cast<int>(spare.size())));
  }
  OrbFeatures features;
  features.keypoints.reserve(kept.size());
  for (int index : kept) features.keypoints.push_back(detected[index]);
  orb_->compute(gray, features.keypoints, features.descriptors);
  if (features.descriptors.empty()) features.descriptors = cv::Mat(0, 32, CV_8UC1);
  ToImagePixelCentres(gray.size(), &features.keypoints);
  return features;
}

void OrbExtractor::ToImagePixelCentres(const cv::Size& image_size,
                                       std::vector<cv::KeyPoint>* keypoints) const {
  for (cv::KeyPoint& k : *keypoints) {
    if (k.octave <= 0) continue;
    // OpenCV resizes level L to round(size / scale^L) pixels (pixel centres aligned, as every
    // resize does) and reports a corner found at (x, y) there as (x, y) * scale^L: scale^L as
    // OpenCV computes it, in float.
    const float scale = static_cast<float>(
        std::pow(static_cast<double>(options_.scale_factor), static_cast<double>(k.octave)));
    const float level_x = k.pt.x / scale;
    const float level_y = k.pt.y / scale;
    const int level_width = cvRound(image_size.width / scale);
    const int level_height = cvRound(image_size.height / scale);
    k.pt.x = (level_x + 0.5f) * image_size.width / level_width - 0.5f;
    k.pt.y = (level_y + 0.5f) * image_size.height / level_height - 0.5f;
  }
}

cv::Mat ToGray(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return image;
  cv::Mat gray;
  if (image.type() == CV_8UC3) {
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  } else if (image.type() == CV_8UC4) {
    cv::cvtColor(image, gray, cv::COLOR_BGRA2GRAY);
  } else {
    assert(false && "ToGray: unsupported image type");
  }
  return gray;
}

}  // namespace visual_loop
}  // namespace fusemap
