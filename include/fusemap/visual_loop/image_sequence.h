#ifndef FUSEMAP_VISUAL_LOOP_IMAGE_SEQUENCE_H_
#define FUSEMAP_VISUAL_LOOP_IMAGE_SEQUENCE_H_

#include <string>
#include <vector>

namespace fusemap {
namespace visual_loop {

// Natural order of file names: runs of digits compare as numbers, so "2.png" < "10.png" and
// "img_9" < "img_10"; otherwise byte order.
bool NaturalLess(const std::string& a, const std::string& b);

// The image files (.png, .jpg, .jpeg, .pgm, .ppm, .bmp, any case) directly in `directory`, in
// natural order of their names, as full paths. Empty with *error set if it cannot be read.
std::vector<std::string> ListImages(const std::string& directory, std::string* error);

}  // namespace visual_loop
}  // namespace fusemap

#endif  // FUSEMAP_VISUAL_LOOP_IMAGE_SEQUENCE_H_
