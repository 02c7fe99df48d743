#ifndef FUSEMAP_TOOLS_VLOOP_VLOOP_COMMON_H_
#define FUSEMAP_TOOLS_VLOOP_VLOOP_COMMON_H_

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "fusemap/sensor/rgbd_frame.h"
#include "fusemap/visual_loop/vocabulary.h"

namespace fusemap {
namespace vloop {

// fx,fy,cx,cy as --intrinsics gives them; false unless there are four and fx, fy > 0.
bool IntrinsicsFromList(const std::vector<double>& fx_fy_cx_cy, sensor::PinholeIntrinsics* out);

// `given` (--vocabulary) unless empty, else the committed one (next to the build tree, or the
// source tree this binary was built from).
std::string VocabularyPath(const std::string& given);
std::optional<visual_loop::Vocabulary> LoadVocabularyOrReport(const std::string& path);

// The image, or an empty Mat after printing "path: cannot read image".
cv::Mat ReadImage(const std::string& path, int flags);

int TrainVocabularyCommand(int argc, char** argv);
int MatchCommand(int argc, char** argv);
int DetectCommand(int argc, char** argv);

}  // namespace vloop
}  // namespace fusemap

#endif  // FUSEMAP_TOOLS_VLOOP_VLOOP_COMMON_H_
