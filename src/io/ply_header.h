#ifndef FUSEMAP_IO_PLY_HEADER_H_
#define FUSEMAP_IO_PLY_HEADER_H_

#include <cstdint>
#include <string>

namespace fusemap {
namespace io {

// Checks a PLY file's header against its size before anyone reads the data: PCL's reader
// allocates what the header declares and then reads element by element, so a header claiming
// 1e9 vertices cost 46 s before the short file was rejected. Every element needs at least
// its fixed-size properties (binary) or two characters per property (ASCII), so the declared
// counts must fit in the bytes after `end_header`. False with `path: reason` otherwise, and
// for a directory, a file that is not PLY or a header that never ends.
bool CheckPlyFileSize(const std::string& path, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_PLY_HEADER_H_
