#ifndef FUSEMAP_IO_WRITE_ALL_H_
#define FUSEMAP_IO_WRITE_ALL_H_

#include <string>

namespace fusemap {
namespace io {

// Writes all of `bytes` to the open file descriptor, retrying short writes and EINTR. False
// (errno set) on the first failing write.
bool WriteAll(int fd, const std::string& bytes);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_WRITE_ALL_H_
