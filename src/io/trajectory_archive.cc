#include "fusemap/io/trajectory_archive.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>

#include "byte_buffer.h"
#include "submap_state_codec.h"
#include "write_all.h"

namespace fusemap {
namespace io {
namespace {

enum File { kNodes = 0, kOdometry = 1 };
constexpr const char* kNames[2] = {"nodes.bin", "odometry.bin"};
constexpr std::uint64_t kRecordBytes[2] = {4 + 4 * 8, 4 * 8};

std::string Errno(const std::string& path, const char* what) {
  return path + ": " + what + ": " + std::strerror(errno);
}

bool ReadAll(const std::string& path, std::uint64_t length, std::uint64_t record_bytes,
             std::string* bytes, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot open";
    return false;
  }
  bytes->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (bytes->size() < length) {
    *error = path + ": " + std::to_string(bytes->size()) + " bytes, the archive wrote " +
             std::to_string(length);
    return false;
  }
  bytes->resize(length);
  if (length % record_bytes != 0) {
    *error = path + ": " + std::to_string(length) + " bytes is not a whole number of records";
    return false;
  }
  return true;
}

}  // namespace

struct TrajectoryArchive::Files {
  int fd[2] = {-1, -1};
  std::string path[2];
  ~Files() {
    for (int f : fd) {
      if (f >= 0) ::close(f);
    }
  }
  bool Append(int i, const std::string& bytes, std::uint64_t* length, std::string* error) {
    if (!WriteAll(fd[i], bytes)) {
      *error = Errno(path[i], "write failed");
      return false;
    }
    if (!bytes.empty() && ::fsync(fd[i]) != 0) {
      *error = Errno(path[i], "fsync failed");
      return false;
    }
    *length += bytes.size();
    return true;
  }
  // Cuts file i back to `length` bytes and appends from there.
  bool CutBack(int i, std::uint64_t length) {
    return ::ftruncate(fd[i], static_cast<off_t>(length)) == 0 && ::lseek(fd[i], 0, SEEK_END) >= 0;
  }
};

TrajectoryArchive::TrajectoryArchive(std::string dir, TrajectoryArchiveMark mark,
                                     std::unique_ptr<Files> files)
    : dir_(std::move(dir)), mark_(mark), files_(std::move(files)) {}

TrajectoryArchive::~TrajectoryArchive() = default;

std::unique_ptr<TrajectoryArchive> TrajectoryArchive::Open(const std::string& dir,
                                                           const TrajectoryArchiveMark* mark,
                                                           std::string* warning,
                                                           std::string* error) {
  warning->clear();
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    *error = "cannot create " + dir + ": " + ec.message();
    return nullptr;
  }
  TrajectoryArchiveMark start = mark != nullptr ? *mark : TrajectoryArchiveMark();
  std::uint64_t* lengths[2] = {&start.nodes_bytes, &start.odometry_bytes};
  for (int i = 0; i < 2; ++i) {
    const std::string path = dir + "/" + kNames[i];
    std::error_code size_ec;
    const auto size = std::filesystem::file_size(path, size_ec);
    if (*lengths[i] > 0 && (size_ec || size < *lengths[i])) {
      *warning = path + " holds " + (size_ec ? std::string("nothing") : std::to_string(size) +
                 " bytes") + ", the checkpoint recorded " + std::to_string(*lengths[i]) +
                 ": the archive starts over (the outputs miss what was archived before)";
      start = TrajectoryArchiveMark();
      break;
    }
  }
  auto files = std::make_unique<Files>();
  for (int i = 0; i < 2; ++i) {
    files->path[i] = dir + "/" + kNames[i];
    files->fd[i] = ::open(files->path[i].c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
    if (files->fd[i] < 0) {
      *error = Errno(files->path[i], "cannot open");
      return nullptr;
    }
    // Whatever was appended after the checkpoint was written is cut off again: the restored
    // state appends it anew.
    if (!files->CutBack(i, *lengths[i])) {
      *error = Errno(files->path[i], "cannot cut back to the checkpoint");
      return nullptr;
    }
  }
  return std::unique_ptr<TrajectoryArchive>(new TrajectoryArchive(dir, start, std::move(files)));
}

bool TrajectoryArchive::Append(const std::vector<pose_graph::ArchivedNode2D>& nodes,
                               std::vector<sensor::OdometryData>* odometry, std::string* error) {
  std::string node_bytes, odometry_bytes;
  ByteWriter node_out(&node_bytes), odometry_out(&odometry_bytes);
  for (const auto& node : nodes) {
    node_out.I32(node.node);
    EncodeTimedPose2d(node.stamp_s, node.T_map_node, &node_out);
  }
  for (const auto& sample : *odometry) EncodeTimedPose2d(sample.stamp_s, sample.pose, &odometry_out);
  const TrajectoryArchiveMark before = mark_;
  if (!files_->Append(kNodes, node_bytes, &mark_.nodes_bytes, error) ||
      !files_->Append(kOdometry, odometry_bytes, &mark_.odometry_bytes, error)) {
    mark_ = before;
    const std::uint64_t lengths[2] = {before.nodes_bytes, before.odometry_bytes};
    for (int i = 0; i < 2; ++i) {
      if (!files_->CutBack(i, lengths[i])) {
        *error += "; and " + Errno(files_->path[i], "cannot cut back");
      }
    }
    return false;
  }
  if (!odometry->empty()) mark_.last_odometry_stamp_s = odometry->back().stamp_s;
  odometry->clear();
  odometry->shrink_to_fit();
  return true;
}

bool TrajectoryArchive::ReadWholeRun(const std::vector<TimedPose2d>& nodes,
                                     const std::vector<sensor::OdometryData>& odometry,
                                     std::vector<TimedPose2d>* all_nodes,
                                     std::vector<sensor::OdometryData>* all_odometry,
                                     std::string* error) const {
  std::string bytes[2];
  const std::uint64_t lengths[2] = {mark_.nodes_bytes, mark_.odometry_bytes};
  for (int i = 0; i < 2; ++i) {
    if (!ReadAll(files_->path[i], lengths[i], kRecordBytes[i], &bytes[i], error)) return false;
  }
  std::vector<std::pair<int, TimedPose2d>> indexed;
  ByteReader node_in(bytes[kNodes].data(), bytes[kNodes].size());
  while (node_in.remaining() > 0) {
    int32_t index = 0;
    TimedPose2d pose;
    if (!node_in.I32(&index) || !DecodeTimedPose2d(&node_in, &pose.stamp_s, &pose.pose)) {
      *error = files_->path[kNodes] + ": " + node_in.error();
      return false;
    }
    indexed.push_back({index, pose});
  }
  // Nodes leave the graph whenever they are trimmed, not in order.
  std::sort(indexed.begin(), indexed.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<TimedPose2d> archived;
  archived.reserve(indexed.size());
  for (const auto& [index, pose] : indexed) archived.push_back(pose);
  all_nodes->clear();
  all_nodes->reserve(archived.size() + nodes.size());
  std::merge(archived.begin(), archived.end(), nodes.begin(), nodes.end(),
             std::back_inserter(*all_nodes),
             [](const TimedPose2d& a, const TimedPose2d& b) { return a.stamp_s < b.stamp_s; });

  all_odometry->clear();
  all_odometry->reserve(bytes[kOdometry].size() / kRecordBytes[kOdometry] + odometry.size());
  ByteReader odometry_in(bytes[kOdometry].data(), bytes[kOdometry].size());
  while (odometry_in.remaining() > 0) {
    sensor::OdometryData sample;
    if (!DecodeTimedPose2d(&odometry_in, &sample.stamp_s, &sample.pose)) {
      *error = files_->path[kOdometry] + ": " + odometry_in.error();
      return false;
    }
    all_odometry->push_back(sample);
  }
  all_odometry->insert(all_odometry->end(), odometry.begin(), odometry.end());
  return true;
}

}  // namespace io
}  // namespace fusemap
