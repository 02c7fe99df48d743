// Converts a CARMEN text log (plain or gzip) into an LCM log: laser scans as
// fusemap_lcm::laser_scan_t, wheel odometry as fusemap_lcm::odometry2d_t, event timestamps =
// message utime. All interpretation (time policy, range limit, beam angles) lives in
// io::CarmenReader and is printed in the summary.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include "fusemap/common/command_line.h"
#include "fusemap/io/carmen_reader.h"
#include "fusemap/io/lcm_conversions.h"
#include "fusemap/io/lcm_log.h"
#include "fusemap/io/stamp_map_file.h"
#include "fusemap/io/tum_trajectory.h"

namespace {

constexpr char kUsage[] =
    "usage: fusemap_carmen2lcm INPUT OUTPUT.lcm [--skip-bad] [--range-max M]\n"
    "                          [--laser-channel LIDAR] [--odom-channel ODOMETRY]\n"
    "                          [--stamp-map FILE] [--reference-poses FILE.tum]\n"
    "  INPUT          CARMEN log (FLASER, ROBOTLASER1, ODOM lines), plain or .gz\n"
    "  --skip-bad     skip and count malformed lines instead of failing\n"
    "  --range-max M  FLASER no-return threshold in metres (default: detected)\n"
    "  --stamp-map FILE  also write each odometry record's output stamp beside the stamp\n"
    "                 the log printed, so ground truth on the log's clock can be looked up\n"
    "                 in trajectory.tum (fusemap_eval relations --stamp-map)\n"
    "  --reference-poses FILE.tum  also write GMapping's pose of each FLASER scan at the\n"
    "                 scan's output stamp (as in fusemap_offline's nodes.tum), to score\n"
    "                 against with fusemap_eval ate\n"
    "Scans: beam i at -90 deg + i * 180 deg / (N - N%2), i.e. 180/181 beams at 1 deg.\n"
    "Exit codes: 0 converted, 1 bad input (no CARMEN records, a malformed line without\n"
    "--skip-bad, an unreadable file) or a failed write, 2 command-line usage error.\n";

struct Args {
  fusemap::io::CarmenOptions options;
  std::string input, output;
  std::string laser_channel = "LIDAR", odom_channel = "ODOMETRY";
  std::string stamp_map_path, reference_path;
};

// Fills *args; nullopt to go on, else the exit code (--help 0, usage error 2).
std::optional<int> ParseArgs(int argc, char** argv, Args* args) {
  fusemap::common::CommandLine command_line("fusemap_carmen2lcm", kUsage);
  command_line.AddPositional("INPUT", &args->input);
  command_line.AddPositional("OUTPUT.lcm", &args->output);
  command_line.AddFlag("--skip-bad", &args->options.skip_bad);
  command_line.AddDouble("--range-max", &args->options.range_max_m,
                         fusemap::common::NumberRange::Positive());
  command_line.AddString("--laser-channel", &args->laser_channel);
  command_line.AddString("--odom-channel", &args->odom_channel);
  command_line.AddString("--stamp-map", &args->stamp_map_path);
  command_line.AddString("--reference-poses", &args->reference_path);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv)) return exit_code;
  // Opening the output truncates it: never when it is the input (or the stamp map) under
  // another name. Compared by file identity, so links and "./X" are caught too.
  std::error_code ec;
  for (const std::string& other : {args->input, args->stamp_map_path}) {
    if (!other.empty() && std::filesystem::equivalent(other, args->output, ec)) {
      return command_line.UsageError("OUTPUT " + args->output + " is the same file as " + other);
    }
  }
  if (!args->stamp_map_path.empty() &&
      std::filesystem::equivalent(args->input, args->stamp_map_path, ec)) {
    return command_line.UsageError("--stamp-map " + args->stamp_map_path +
                                   " is the same file as INPUT");
  }
  return std::nullopt;
}

// Converts the log and prints the summary: 0, or 1 for bad input or a failed write (no
// half-converted output is left behind).
int Convert(const Args& args) {
  const std::string& input = args.input;
  const std::string& output = args.output;
  const std::string& stamp_map_path = args.stamp_map_path;
  const std::string& reference_path = args.reference_path;
  std::string error;
  fusemap::io::CarmenReader reader(args.options);
  if (!reader.Open(input, &error)) {
    std::cerr << error << "\n";
    return 1;
  }
  if (!stamp_map_path.empty() && reader.summary().time_policy == "synthesized") {
    std::cerr << "--stamp-map: " << input << " has no usable stamps ("
              << reader.summary().time_reason << "); time is synthesized from line order\n";
    return 1;
  }
  fusemap::io::StampMapWriter stamp_map;
  if (!stamp_map_path.empty() && !stamp_map.Open(stamp_map_path, &error)) {
    std::cerr << error << "\n";
    return 1;
  }
  fusemap::io::LcmLogWriter writer;
  if (!writer.Open(output, &error)) {
    std::cerr << error << "\n";
    return 1;
  }
  fusemap::io::CarmenRecord record;
  fusemap::eval::Trajectory reference;
  while (reader.Next(&record, &error)) {
    bool ok = false;
    if (record.kind == fusemap::io::CarmenRecord::Kind::kLaser) {
      const auto bytes = fusemap::io::EncodeLaserScan(record.scan);
      ok = writer.Write(args.laser_channel, fusemap::io::StampToUtime(record.scan.stamp_s),
                        bytes.data(), static_cast<int>(bytes.size()));
    } else {
      const auto bytes = fusemap::io::EncodeOdometry(
          record.odometry, record.linear_velocity_mps, record.angular_velocity_radps);
      ok = writer.Write(args.odom_channel, fusemap::io::StampToUtime(record.odometry.stamp_s),
                        bytes.data(), static_cast<int>(bytes.size()));
    }
    if (!ok) {
      error = output + ": write failed";
      break;
    }
    if (record.has_reference_pose) {
      reference.push_back({record.scan.stamp_s,
                           fusemap::common::Rigid3d::FromRigid2d(record.reference_pose)});
    }
    // Odometry only: a relation's pose is looked up in trajectory.tum, sampled at the odometry.
    if (!stamp_map_path.empty() && record.kind == fusemap::io::CarmenRecord::Kind::kOdometry &&
        !stamp_map.Add(
            {record.odometry.stamp_s, record.log_stamp_s, record.log_stamp_resolution_s})) {
      error = stamp_map_path + ": write failed";
      break;
    }
    if (writer.num_written() % 10000 == 0) {
      std::cerr << "  " << writer.num_written() << " messages, line " << record.line << "\n";
    }
  }
  writer.Close();
  std::string close_error;
  if (!stamp_map_path.empty() && !stamp_map.Close(&close_error) && error.empty()) {
    error = close_error;
  }
  if (error.empty() && !reference_path.empty()) {
    fusemap::io::WriteTumTrajectoryFile(reference_path, reference, &error);
  }
  if (!error.empty()) {
    std::cerr << error << "\n";
    std::remove(output.c_str());  // no half-converted output
    if (!stamp_map_path.empty()) std::remove(stamp_map_path.c_str());
    if (!reference_path.empty()) std::remove(reference_path.c_str());
    return 1;
  }
  const fusemap::io::CarmenSummary& s = reader.summary();
  for (const std::string& reason : s.first_skip_reasons) std::cerr << "skipped " << reason << "\n";
  if (s.lasers == 0 && s.odometry == 0) {
    std::cerr << input << ": no CARMEN records found (" << s.lines
              << " non-empty lines, none FLASER, ROBOTLASER1 or ODOM); is it a CARMEN log?\n"
              << s.ToString() << "\n";
    std::remove(output.c_str());
    if (!stamp_map_path.empty()) std::remove(stamp_map_path.c_str());
    return 1;
  }
  std::cout << s.ToString() << " wrote=" << output;
  if (!stamp_map_path.empty()) std::cout << " stamp_map=" << stamp_map_path;
  if (!reference_path.empty()) {
    std::cout << " reference_poses=" << reference.size() << " " << reference_path;
  }
  std::cout << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (const auto exit_code = ParseArgs(argc, argv, &args)) return *exit_code;
  return Convert(args);
}
