#include "fusemap/ground_truth/tag_detector.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag25h9.h>
#include <apriltag/tag36h11.h>
#include <apriltag/tagStandard41h12.h>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace fusemap {
namespace ground_truth {

struct TagDetector::Impl {
  apriltag_family_t* family = nullptr;
  void (*destroy_family)(apriltag_family_t*) = nullptr;
  apriltag_detector_t* detector = nullptr;
};

namespace {

bool CreateFamily(const std::string& name, apriltag_family_t** family,
                  void (**destroy)(apriltag_family_t*)) {
  if (name == "tag36h11") {
    *family = tag36h11_create();
    *destroy = tag36h11_destroy;
  } else if (name == "tag25h9") {
    *family = tag25h9_create();
    *destroy = tag25h9_destroy;
  } else if (name == "tagStandard41h12") {
    *family = tagStandard41h12_create();
    *destroy = tagStandard41h12_destroy;
  } else {
    return false;
  }
  return true;
}

}  // namespace

void TagDetectorOptions::Check(common::OptionChecker* check) const {
  check->Require(family == "tag36h11" || family == "tag25h9" || family == "tagStandard41h12",
                 "family", "'" + family + "' is not tag36h11, tag25h9 or tagStandard41h12");
  check->Require(quad_decimate >= 1.0, "quad_decimate", "must be >= 1");
  check->Require(quad_sigma >= 0.0, "quad_sigma", "must be >= 0");
  check->Require(nthreads >= 1, "nthreads", "must be >= 1");
  check->Require(max_hamming >= 0 && max_hamming <= 3, "max_hamming", "must be in [0, 3]");
}

bool TagDetectorOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

TagDetectorOptions ParseTagDetectorOptions(common::ConfigReader& reader) {
  TagDetectorOptions options;
  reader.Get("family", &options.family);
  reader.Get("quad_decimate", &options.quad_decimate);
  reader.Get("quad_sigma", &options.quad_sigma);
  reader.Get("refine_edges", &options.refine_edges);
  reader.Get("nthreads", &options.nthreads);
  reader.Get("max_hamming", &options.max_hamming);
  reader.CheckOptions(options);
  return options;
}

std::unique_ptr<TagDetector> TagDetector::Create(const TagDetectorOptions& options,
                                                 std::string* error) {
  if (!options.IsValid(error)) return nullptr;
  auto impl = std::make_unique<Impl>();
  if (!CreateFamily(options.family, &impl->family, &impl->destroy_family)) {
    *error = "unknown tag family '" + options.family + "'";
    return nullptr;
  }
  impl->detector = apriltag_detector_create();
  apriltag_detector_add_family_bits(impl->detector, impl->family, options.max_hamming);
  impl->detector->quad_decimate = static_cast<float>(options.quad_decimate);
  impl->detector->quad_sigma = static_cast<float>(options.quad_sigma);
  impl->detector->refine_edges = options.refine_edges;
  impl->detector->nthreads = options.nthreads;
  return std::unique_ptr<TagDetector>(new TagDetector(options, std::move(impl)));
}

TagDetector::TagDetector(const TagDetectorOptions& options, std::unique_ptr<Impl> impl)
    : options_(options), impl_(std::move(impl)) {}

TagDetector::~TagDetector() {
  apriltag_detector_destroy(impl_->detector);
  impl_->destroy_family(impl_->family);
}

int TagDetector::MinImageSidePx() const {
  // The smallest family (tag25h9) is 9 cells wide with its white border; at two pixels per
  // cell that is 18 pixels.
  constexpr int kMinTagSidePx = 18;
  constexpr int kMinDecimatedSidePx = 8;
  return std::max(kMinTagSidePx, static_cast<int>(std::ceil(kMinDecimatedSidePx * options_.quad_decimate)));
}

std::vector<TagDetection> TagDetector::Detect(const GreyImage& image) const {
  assert(image.pixels.size() == static_cast<size_t>(image.width) * image.height);
  if (image.width < MinImageSidePx() || image.height < MinImageSidePx()) return {};
  // The library only reads the buffer; image_u8_t merely lacks const.
  image_u8_t view{image.width, image.height, image.width,
                  const_cast<uint8_t*>(image.pixels.data())};
  zarray_t* raw = apriltag_detector_detect(impl_->detector, &view);
  std::vector<TagDetection> detections;
  detections.reserve(zarray_size(raw));
  for (int i = 0; i < zarray_size(raw); ++i) {
    apriltag_detection_t* det = nullptr;
    zarray_get(raw, i, &det);
    TagDetection out;
    out.id = det->id;
    out.hamming = det->hamming;
    out.decision_margin = det->decision_margin;
    out.center_px = Eigen::Vector2d(det->c[0], det->c[1]);
    for (int k = 0; k < 4; ++k) out.corners_px[k] = Eigen::Vector2d(det->p[k][0], det->p[k][1]);
    detections.push_back(out);
  }
  apriltag_detections_destroy(raw);
  std::sort(detections.begin(), detections.end(), [](const TagDetection& a, const TagDetection& b) {
    return a.id != b.id ? a.id < b.id : a.center_px.x() < b.center_px.x();
  });
  return detections;
}

GreyImage GreyFromRgb(int width, int height, const std::vector<uint8_t>& rgb) {
  assert(rgb.size() == static_cast<size_t>(width) * height * 3);
  GreyImage grey;
  grey.width = width;
  grey.height = height;
  grey.pixels.resize(static_cast<size_t>(width) * height);
  for (size_t i = 0; i < grey.pixels.size(); ++i) {
    const double y = 0.299 * rgb[3 * i] + 0.587 * rgb[3 * i + 1] + 0.114 * rgb[3 * i + 2];
    grey.pixels[i] = static_cast<uint8_t>(std::lround(std::min(255.0, y)));
  }
  return grey;
}

}  // namespace ground_truth
}  // namespace fusemap
