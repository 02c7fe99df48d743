#include "fusemap/io/trajectory_archive.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <utility>

#include "fusemap/io/tum_trajectory.h"

namespace fusemap {
namespace io {
namespace {

constexpr const char* kNames[3] = {"trajectory.tum", "nodes.tum", "odometry.tum"};

std::string Errno(const std::string& path, const char* what) {
  return path + ": " + what + ": " + std::strerror(errno);
}

eval::TimedPose3d ToPose3d(double stamp_s, const common::Rigid2d& pose) {
  return {stamp_s, common::Rigid3d::FromRigid2d(pose)};
}

}  // namespace

struct TrajectoryArchive::Files {
  int fd[3] = {-1, -1, -1};
  std::string path[3];
  ~Files() {
    for (int f : fd) {
      if (f >= 0) ::close(f);
    }
  }
  bool Append(int i, const std::string& bytes, std::uint64_t* length, std::string* error) {
    size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd[i], bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        *error = Errno(path[i], "write failed");
        return false;
      }
      done += static_cast<size_t>(n);
    }
    if (::fsync(fd[i]) != 0) {
      *error = Errno(path[i], "fsync failed");
      return false;
    }
    *length += bytes.size();
    return true;
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
  auto files = std::make_unique<Files>();
  TrajectoryArchiveMark start = mark != nullptr ? *mark : TrajectoryArchiveMark();
  std::uint64_t lengths[3] = {start.trajectory_bytes, start.nodes_bytes, start.odometry_bytes};
  for (int i = 0; i < 3; ++i) {
    std::error_code size_ec;
    const auto size = std::filesystem::file_size(dir + "/" + kNames[i], size_ec);
    if (lengths[i] > 0 && (size_ec || size < lengths[i])) {
      *warning = dir + "/" + kNames[i] + " holds " + (size_ec ? "nothing" : std::to_string(size) +
                 " bytes") + ", the checkpoint recorded " + std::to_string(lengths[i]) +
                 ": the archive starts over (the outputs miss the part archived before)";
      start.trajectory_bytes = start.nodes_bytes = start.odometry_bytes = 0;
      for (auto& length : lengths) length = 0;
      break;
    }
  }
  for (int i = 0; i < 3; ++i) {
    files->path[i] = dir + "/" + kNames[i];
    // Without a mark the archive starts empty; with one, whatever was appended after that
    // checkpoint was written is cut off again (the restored state will append it anew).
    const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | (mark == nullptr ? O_TRUNC : 0);
    files->fd[i] = ::open(files->path[i].c_str(), flags, 0644);
    if (files->fd[i] < 0) {
      *error = Errno(files->path[i], "cannot open");
      return nullptr;
    }
    if (::ftruncate(files->fd[i], static_cast<off_t>(lengths[i])) != 0 ||
        ::lseek(files->fd[i], 0, SEEK_END) < 0) {
      *error = Errno(files->path[i], "cannot cut back to the checkpoint");
      return nullptr;
    }
  }
  return std::unique_ptr<TrajectoryArchive>(new TrajectoryArchive(dir, start, std::move(files)));
}

std::vector<TrajectoryArchive::TimedPose2d> TrajectoryArchive::WithLastNode(
    const std::vector<TimedPose2d>& nodes) const {
  std::vector<TimedPose2d> out;
  out.reserve(nodes.size() + 1);
  if (mark_.has_last_node) out.push_back({mark_.last_node.stamp_s, mark_.last_node.T_map_node});
  out.insert(out.end(), nodes.begin(), nodes.end());
  return out;
}

std::vector<sensor::OdometryData> TrajectoryArchive::WithCarry(
    const std::vector<sensor::OdometryData>& odometry) const {
  std::vector<sensor::OdometryData> out;
  out.reserve(odometry.size() + 1);
  if (mark_.has_carry) out.push_back(mark_.carry);
  out.insert(out.end(), odometry.begin(), odometry.end());
  return out;
}

bool TrajectoryArchive::Append(const std::vector<pose_graph::ArchivedNode2D>& nodes,
                               std::vector<sensor::OdometryData>* odometry, std::string* error) {
  if (nodes.empty()) return true;
  std::vector<TimedPose2d> new_nodes;
  for (const auto& node : nodes) new_nodes.push_back({node.stamp_s, node.T_map_node});
  const double end_s = nodes.back().stamp_s;
  // Samples before the newest archived node lie between archived nodes (or before the first),
  // so their poses are final; from end_s on they also depend on the nodes still in the graph.
  eval::Trajectory dense, node_lines, odometry_lines;
  if (!odometry->empty() || mark_.has_carry) {
    for (const auto& pose : pose_graph::DensifyWithOdometry(WithLastNode(new_nodes),
                                                            WithCarry(*odometry))) {
      if (pose.stamp_s <= mark_.last_output_stamp_s || pose.stamp_s >= end_s) continue;
      dense.push_back(ToPose3d(pose.stamp_s, pose.pose));
      mark_.last_output_stamp_s = pose.stamp_s;
    }
  }
  double last_node_s = mark_.has_last_node ? mark_.last_node.stamp_s
                                           : -std::numeric_limits<double>::infinity();
  for (const auto& node : nodes) {
    if (node.stamp_s <= last_node_s) continue;
    node_lines.push_back(ToPose3d(node.stamp_s, node.T_map_node));
    last_node_s = node.stamp_s;
  }
  size_t settled = 0;
  while (settled < odometry->size() && (*odometry)[settled].stamp_s < end_s) {
    const sensor::OdometryData& sample = (*odometry)[settled++];
    if (sample.stamp_s <= mark_.last_odometry_stamp_s) continue;
    odometry_lines.push_back(ToPose3d(sample.stamp_s, sample.pose));
    mark_.last_odometry_stamp_s = sample.stamp_s;
  }
  if (settled > 0) {
    mark_.has_carry = true;
    mark_.carry = (*odometry)[settled - 1];
    odometry->erase(odometry->begin(), odometry->begin() + static_cast<std::ptrdiff_t>(settled));
  }
  mark_.has_last_node = true;
  mark_.last_node = nodes.back();
  return files_->Append(0, FormatTumLines(dense), &mark_.trajectory_bytes, error) &&
         files_->Append(1, FormatTumLines(node_lines), &mark_.nodes_bytes, error) &&
         files_->Append(2, FormatTumLines(odometry_lines), &mark_.odometry_bytes, error);
}

bool TrajectoryArchive::ReadWholeRun(const std::vector<TimedPose2d>& nodes,
                                     const std::vector<sensor::OdometryData>& odometry,
                                     eval::Trajectory* trajectory, eval::Trajectory* all_nodes,
                                     eval::Trajectory* all_odometry, std::string* error) const {
  eval::Trajectory* out[3] = {trajectory, all_nodes, all_odometry};
  for (int i = 0; i < 3; ++i) {
    if (!ReadTumTrajectoryFile(files_->path[i], out[i], error)) return false;
  }
  const auto append = [](eval::Trajectory* to, double stamp_s, const common::Rigid2d& pose) {
    if (to->empty() || stamp_s > to->back().stamp_s) to->push_back(ToPose3d(stamp_s, pose));
  };
  if (!odometry.empty() || mark_.has_carry) {
    for (const auto& pose :
         pose_graph::DensifyWithOdometry(WithLastNode(nodes), WithCarry(odometry))) {
      if (pose.stamp_s > mark_.last_output_stamp_s) append(trajectory, pose.stamp_s, pose.pose);
    }
  } else {
    for (const auto& node : nodes) append(trajectory, node.stamp_s, node.pose);
  }
  for (const auto& node : nodes) append(all_nodes, node.stamp_s, node.pose);
  for (const auto& sample : odometry) append(all_odometry, sample.stamp_s, sample.pose);
  return true;
}

}  // namespace io
}  // namespace fusemap
