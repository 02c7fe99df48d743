#ifndef FUSEMAP_IO_WRITE_ALL_H_
#define FUSEMAP_IO_WRITE_ALL_H_

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace fusemap {
namespace io {

// Writes all of `bytes` to the open file descriptor, retrying short writes and EINTR. False
// (errno set) on the first failing write.
bool WriteAll(int fd, const std::string& bytes);
bool WriteAll(int fd, const void* data, size_t size);

// Replaces `path` with `bytes` so that a reader (or a crash, or a full disk) sees either the old
// file or the whole new one: written to `path`.tmp in the same folder, every write checked,
// fsynced, renamed over `path`. On failure the temporary is removed, `path` is left as it was
// and *error reads "<path>: <what failed>: <strerror>".
bool WriteFileAtomically(const std::string& path, const std::string& bytes, std::string* error);

// Bytes that stay where they are: a large image is written from its own buffer, not copied.
struct ByteSpan {
  const void* data;
  size_t size;
};
// The pieces one after the other, as one file.
bool WriteFileAtomically(const std::string& path, const std::vector<ByteSpan>& pieces,
                         std::string* error);

// The same for writers that only take a file name (PCL): `write(tmp_path, error)` fills the
// temporary, which is then fsynced and renamed. The library's own error checks are all there is
// for its writes; fsync still reports what the file system deferred.
using PathWriter = std::function<bool(const std::string& tmp_path, std::string* error)>;
bool WriteFileAtomically(const std::string& path, const PathWriter& write, std::string* error);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_WRITE_ALL_H_
