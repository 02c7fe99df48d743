#include "write_all.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace fusemap {
namespace io {
namespace {

bool Fail(const std::string& path, const std::string& what, int errno_value, std::string* error) {
  if (error != nullptr) *error = path + ": " + what + ": " + std::strerror(errno_value);
  return false;
}

// fsync of `tmp` (already complete), then rename over `path` and fsync of the folder so that
// the rename itself survives a power cut.
bool SyncAndRename(const std::string& tmp, const std::string& path, std::string* error) {
  const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Fail(path, "cannot reopen " + tmp, errno, error);
  if (::fsync(fd) != 0) {
    const int saved = errno;
    ::close(fd);
    return Fail(path, "fsync failed", saved, error);
  }
  if (::close(fd) != 0) return Fail(path, "close failed", errno, error);
  if (::rename(tmp.c_str(), path.c_str()) != 0) return Fail(path, "rename failed", errno, error);
  const size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);  // best effort: some file systems refuse fsync on folders
    ::close(dir_fd);
  }
  return true;
}

}  // namespace

bool WriteAll(int fd, const std::string& bytes) { return WriteAll(fd, bytes.data(), bytes.size()); }

bool WriteAll(int fd, const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) errno = ENOSPC;  // write(2) made no progress: treat as a full device
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

bool WriteFileAtomically(const std::string& path, const std::string& bytes, std::string* error) {
  return WriteFileAtomically(path, {{bytes.data(), bytes.size()}}, error);
}

bool WriteFileAtomically(const std::string& path, const std::vector<ByteSpan>& pieces,
                         std::string* error) {
  return WriteFileAtomically(
      path,
      [&](const std::string& tmp, std::string* write_error) {
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (fd < 0) return Fail(path, "cannot open " + tmp + " for writing", errno, write_error);
        bool written = true;
        for (const ByteSpan& piece : pieces) {
          written = written && WriteAll(fd, piece.data, piece.size);
        }
        if (!written) {
          const int saved = errno;
          ::close(fd);
          return Fail(path, "write failed", saved, write_error);
        }
        if (::close(fd) != 0) return Fail(path, "close failed", errno, write_error);
        return true;
      },
      error);
}

bool WriteFileAtomically(const std::string& path, const PathWriter& write, std::string* error) {
  const std::string tmp = path + ".tmp";
  if (!write(tmp, error) || !SyncAndRename(tmp, path, error)) {
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

}  // namespace io
}  // namespace fusemap
