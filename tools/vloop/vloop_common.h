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

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 1;
constexpr int kExitUsage = 2;

// Options of a subcommand: positional arguments and "--name value" pairs (flags have no value).
struct Arguments {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::string>> options;
  bool help = false;
  // The value of --name, if given.
  std::optional<std::string> Get(const std::string& name) const;
};

// Parses argv[first..]; options taking a value are listed in `with_value`, the flags in `flags`.
// Returns false with a message on an unknown option or a missing value.
bool ParseArguments(int argc, char** argv, int first, const std::vector<std::string>& with_value,
                    const std::vector<std::string>& flags, Arguments* out, std::string* error);

bool ParseIntrinsics(const std::string& text, sensor::PinholeIntrinsics* out);
bool ParseInt(const std::string& text, int* out);
bool ParseDouble(const std::string& text, double* out);

// --vocabulary if given, else the committed one (next to the build tree, or the source tree
// this binary was built from).
std::string VocabularyPath(const Arguments& arguments);
std::optional<visual_loop::Vocabulary> LoadVocabularyOrReport(const std::string& path);

// The image, or an empty Mat after printing "path: cannot read image".
cv::Mat ReadImage(const std::string& path, int flags);

int TrainVocabularyCommand(int argc, char** argv);
int MatchCommand(int argc, char** argv);
int DetectCommand(int argc, char** argv);

}  // namespace vloop
}  // namespace fusemap

#endif  // FUSEMAP_TOOLS_VLOOP_VLOOP_COMMON_H_
