#ifndef FUSEMAP_GROUND_TRUTH_TAG_DETECTOR_H_
#define FUSEMAP_GROUND_TRUTH_TAG_DETECTOR_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fusemap/common/config_reader.h"

namespace fusemap {
namespace ground_truth {

// An 8-bit grey image, row-major, `width` bytes per row.
struct GreyImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;
};

struct TagDetectorOptions {
  // "tag36h11" (default), "tag25h9" or "tagStandard41h12".
  std::string family = "tag36h11";
  // 1.0 keeps full resolution for corner accuracy; larger is faster but coarser.
  double quad_decimate = 1.0;
  double quad_sigma = 0.0;
  // Off by default: on small (~15 px) tags refinement moves corners by up to a pixel against
  // the reference detections (../shared/data/apriltag) and loses the smallest tag.
  bool refine_edges = false;
  int nthreads = 1;
  // Bits the decoder may correct; more than 2 costs a lot of memory and raises false positives.
  int max_hamming = 2;

  // Each field's rule, against its key (see common::OptionChecker).
  void Check(common::OptionChecker* check) const;
  // The first problem, as "<key> <why>".
  bool IsValid(std::string* error) const;
};

TagDetectorOptions ParseTagDetectorOptions(common::ConfigReader& reader);

// One detected tag. Corner order and pixel convention are those of AprilTag 3: corners wrap
// counter-clockwise in the image (y down) around the tag, corners[0] being the tag's
// bottom-left when the tag is viewed upright (as apriltag_to_image renders it), then
// bottom-right, top-right, top-left. Coordinates put the centre of pixel (u, v) at (u + 0.5,
// v + 0.5), i.e. the image spans [0, width] x [0, height]. In the tag frame used by
// tag_pose.h (x right, y up, z out of the printed face) corners[i] is at
// (s/2) * {(-1,-1), (1,-1), (1,1), (-1,1)}[i].
struct TagDetection {
  int id = -1;
  int hamming = 0;
  double decision_margin = 0.0;
  Eigen::Vector2d center_px = Eigen::Vector2d::Zero();
  std::array<Eigen::Vector2d, 4> corners_px = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(),
                                               Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
};

// Wraps an AprilTag 3 detector for one family. Not copyable; not thread-safe (the library's
// detector keeps scratch state), so use one instance per thread.
class TagDetector {
 public:
  // Returns nullptr and fills *error for an invalid option set or unknown family.
  static std::unique_ptr<TagDetector> Create(const TagDetectorOptions& options, std::string* error);
  ~TagDetector();
  TagDetector(const TagDetector&) = delete;
  TagDetector& operator=(const TagDetector&) = delete;

  // Detections sorted by id, then by centre x. An image narrower or lower than
  // MinImageSidePx() holds no tag and gives none (libapriltag itself crashes on such images).
  std::vector<TagDetection> Detect(const GreyImage& image) const;
  // The smallest side a tag fits in, and that the decimated image still has two of the
  // library's 4-pixel threshold tiles across.
  int MinImageSidePx() const;

  const TagDetectorOptions& options() const { return options_; }

 private:
  struct Impl;
  TagDetector(const TagDetectorOptions& options, std::unique_ptr<Impl> impl);

  TagDetectorOptions options_;
  std::unique_ptr<Impl> impl_;
};

// Luma (ITU-R BT.601) of a packed 8-bit RGB buffer of width*height*3 bytes.
GreyImage GreyFromRgb(int width, int height, const std::vector<uint8_t>& rgb);

}  // namespace ground_truth
}  // namespace fusemap

#endif  // FUSEMAP_GROUND_TRUTH_TAG_DETECTOR_H_
