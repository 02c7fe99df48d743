#include "fusemap/io/checkpoint.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <utility>

#include "byte_buffer.h"
#include "map_builder_state_codec.h"
#include "submap_state_codec.h"
#include "write_all.h"

namespace fusemap {
namespace io {
namespace {

constexpr char kMagic[12] = {'F', 'U', 'S', 'E', 'M', 'A', 'P', 'C', 'K', 'P', 'T', '\0'};
constexpr size_t kHeaderBytes = 36;
// The header checksum covers everything before it.
constexpr size_t kHeaderCrcOffset = 32;
// Far above any map; a larger file is not a checkpoint of ours and is not read into memory.
constexpr uint64_t kMaxFileBytes = uint64_t{8} << 30;

uint32_t Crc32(const char* data, size_t size) {
  uLong crc = crc32(0L, Z_NULL, 0);
  // crc32 takes a uInt length; feed large buffers in pieces.
  while (size > 0) {
    const uInt chunk = static_cast<uInt>(std::min<size_t>(size, 1u << 30));
    crc = crc32(crc, reinterpret_cast<const Bytef*>(data), chunk);
    data += chunk;
    size -= chunk;
  }
  return static_cast<uint32_t>(crc);
}

std::string Errno(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

bool FsyncDirectoryOf(const std::string& path, std::string* error) {
  const size_t slash = path.find_last_of('/');
  const std::string dir =
      slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) {
    *error = Errno("cannot open directory", dir);
    return false;
  }
  const bool ok = ::fsync(fd) == 0;
  if (!ok) *error = Errno("cannot fsync directory", dir);
  ::close(fd);
  return ok;
}

void EncodeOdometry(const std::vector<sensor::OdometryData>& odometry, ByteWriter* out) {
  out->U64(odometry.size());
  for (const auto& o : odometry) EncodeTimedPose2d(o.stamp_s, o.pose, out);
}

bool DecodeOdometry(ByteReader* in, std::vector<sensor::OdometryData>* odometry) {
  size_t n = 0;
  if (!in->Count(8 + 24, &n)) return false;
  odometry->resize(n);
  for (auto& o : *odometry) {
    if (!DecodeTimedPose2d(in, &o.stamp_s, &o.pose)) return false;
  }
  for (size_t i = 1; i < n; ++i) {
    if (!((*odometry)[i].stamp_s >= (*odometry)[i - 1].stamp_s)) {
      in->Fail("odometry record goes back in time");
      return false;
    }
  }
  return true;
}

void EncodeArchiveMark(const TrajectoryArchiveMark& m, ByteWriter* out) {
  out->U64(m.nodes_bytes);
  out->U64(m.odometry_bytes);
  out->F64(m.last_odometry_stamp_s);
}

bool DecodeArchiveMark(ByteReader* in, TrajectoryArchiveMark* m) {
  return in->U64(&m->nodes_bytes) && in->U64(&m->odometry_bytes) &&
         in->F64(&m->last_odometry_stamp_s);
}

}  // namespace

std::string EncodeCheckpoint(const CheckpointContents& contents, bool compress_grids) {
  std::string payload;
  ByteWriter writer(&payload);
  writer.Bytes(contents.fusemap_version);
  writer.Bytes(contents.options_yaml);
  EncodeMapBuilderState(contents.state, compress_grids, &writer);
  EncodeOdometry(contents.odometry, &writer);
  EncodeArchiveMark(contents.archive, &writer);

  std::string file(kMagic, sizeof(kMagic));
  ByteWriter header(&file);
  header.U32(kCheckpointFormatVersion);
  header.U32(0);
  header.U64(payload.size());
  header.U32(Crc32(payload.data(), payload.size()));
  header.U32(Crc32(file.data(), kHeaderCrcOffset));
  file += payload;
  return file;
}

bool DecodeCheckpoint(const std::string& bytes, const std::string& name,
                      CheckpointContents* contents, std::string* error) {
  if (bytes.size() < sizeof(kMagic) ||
      std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    *error = name + ": not a fusemap checkpoint (bad magic)";
    return false;
  }
  if (bytes.size() < kHeaderBytes) {
    *error = name + ": truncated: " + std::to_string(bytes.size()) +
             " bytes, the header alone has " +
             std::to_string(kHeaderBytes);
    return false;
  }
  ByteReader header(bytes.data() + sizeof(kMagic), kHeaderBytes - sizeof(kMagic));
  uint32_t version = 0, flags = 0, payload_crc = 0, header_crc = 0;
  uint64_t payload_bytes = 0;
  header.U32(&version);
  header.U32(&flags);
  header.U64(&payload_bytes);
  header.U32(&payload_crc);
  header.U32(&header_crc);
  if (version != kCheckpointFormatVersion) {
    *error = name + ": checkpoint format version " + std::to_string(version) +
             ", this build reads version " + std::to_string(kCheckpointFormatVersion);
    return false;
  }
  if (header_crc != Crc32(bytes.data(), kHeaderCrcOffset)) {
    *error = name + ": header checksum mismatch (corrupted file)";
    return false;
  }
  if (flags != 0) {
    *error = name + ": unknown header flags " + std::to_string(flags);
    return false;
  }
  const uint64_t present = bytes.size() - kHeaderBytes;
  if (payload_bytes != present) {
    *error = name + (payload_bytes > present ? ": truncated: " : ": trailing data: ") +
             "header announces " + std::to_string(payload_bytes) + " payload bytes, file has " +
             std::to_string(present);
    return false;
  }
  const char* payload = bytes.data() + kHeaderBytes;
  if (payload_crc != Crc32(payload, present)) {
    *error = name + ": payload checksum mismatch (corrupted file)";
    return false;
  }
  ByteReader reader(payload, present);
  CheckpointContents decoded;
  if (!reader.Bytes(&decoded.fusemap_version) || !reader.Bytes(&decoded.options_yaml) ||
      !DecodeMapBuilderState(&reader, &decoded.state) ||
      !DecodeOdometry(&reader, &decoded.odometry) ||
      !DecodeArchiveMark(&reader, &decoded.archive)) {
    *error = name + ": invalid state " + reader.error();
    return false;
  }
  if (reader.remaining() != 0) {
    *error = name + ": " + std::to_string(reader.remaining()) + " unread bytes after the state";
    return false;
  }
  *contents = std::move(decoded);
  return true;
}

bool WriteCheckpoint(const std::string& path, const CheckpointContents& contents,
                     std::string* error, bool compress_grids) {
  const std::string bytes = EncodeCheckpoint(contents, compress_grids);
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    *error = Errno("cannot create", tmp);
    return false;
  }
  if (!WriteAll(fd, bytes) || ::fsync(fd) != 0) {
    *error = Errno("cannot write", tmp);
    ::close(fd);
    ::unlink(tmp.c_str());
    return false;
  }
  if (::close(fd) != 0) {
    *error = Errno("cannot close", tmp);
    ::unlink(tmp.c_str());
    return false;
  }
  struct stat info;
  if (::stat(path.c_str(), &info) == 0 && ::rename(path.c_str(), (path + ".prev").c_str()) != 0) {
    *error = Errno("cannot keep the previous checkpoint as", path + ".prev");
    ::unlink(tmp.c_str());
    return false;
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    *error = Errno("cannot rename " + tmp + " to", path);
    return false;
  }
  return FsyncDirectoryOf(path, error);
}

bool ReadCheckpoint(const std::string& path, CheckpointContents* contents, std::string* error) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) {
    *error = Errno("cannot open", path);
    return false;
  }
  const std::streamoff size = in.tellg();
  if (size < 0 || static_cast<uint64_t>(size) > kMaxFileBytes) {
    *error = path + ": implausible file size " + std::to_string(size);
    return false;
  }
  std::string bytes(static_cast<size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(&bytes[0], size)) {
    *error = path + ": read error";
    return false;
  }
  return DecodeCheckpoint(bytes, path, contents, error);
}

bool ReadLatestCheckpoint(const std::string& path, CheckpointContents* contents,
                          std::string* used_path, std::string* error) {
  std::string primary_error;
  if (ReadCheckpoint(path, contents, &primary_error)) {
    *used_path = path;
    error->clear();
    return true;
  }
  const std::string prev = path + ".prev";
  std::string prev_error;
  if (ReadCheckpoint(prev, contents, &prev_error)) {
    *used_path = prev;
    *error = primary_error + "; fell back to " + prev;
    return true;
  }
  *error = primary_error + "; " + prev_error;
  return false;
}

}  // namespace io
}  // namespace fusemap
