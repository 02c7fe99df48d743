// fusemap_eval: trajectory accuracy metrics (Kümmerle relations, ATE, RPE) over TUM files.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "fusemap/eval/absolute_trajectory_error.h"
#include "fusemap/eval/relation_error.h"
#include "fusemap/eval/relative_pose_error.h"
#include "fusemap/io/relations_file.h"
#include "fusemap/io/stamp_map_file.h"
#include "fusemap/io/tum_trajectory.h"

namespace fusemap {
namespace {

constexpr char kUsage[] =
    "usage: fusemap_eval <command> [options]\n"
    "commands:\n"
    "  relations  Kuemmerle et al. (2009) relation error of a trajectory\n"
    "  ate        absolute trajectory error between two TUM trajectories\n"
    "  rpe        relative pose error between two TUM trajectories\n"
    "Run 'fusemap_eval <command> --help' for the options of a command.\n";

constexpr char kRelationsUsage[] =
    "usage: fusemap_eval relations --relations FILE --trajectory TUM [--time-offset S]\n"
    "                              [--max-time-gap S] [--stamp-map FILE]\n"
    "  --relations FILE   lines 't1 t2 dx dy dz droll dpitch dyaw' (true motion t1 -> t2)\n"
    "  --trajectory TUM   estimated trajectory, 't x y z qx qy qz qw' per line\n"
    "  --time-offset S    subtracted from relation stamps (default 0)\n"
    "  --max-time-gap S   max distance from a relation stamp to a trajectory sample\n"
    "                     (default 0.05); poses between samples are interpolated\n"
    "  --stamp-map FILE   relation stamps are on the raw log's clock: look them up at the\n"
    "                     records that printed them (fusemap_carmen2lcm --stamp-map)\n"
    "Last line: trans_mean_m=... trans_std_m=... rot_mean_deg=... rot_std_deg=...\n";

constexpr char kAteUsage[] =
    "usage: fusemap_eval ate --gt A.tum --est B.tum [--no-align] [--se2] [--max-time-diff S]\n"
    "                        [--interpolate S]\n"
    "  --no-align          do not rigidly align the estimate to the ground truth\n"
    "  --se2               align in the plane only (x, y, yaw; never mirrors the plane)\n"
    "  --max-time-diff S   association tolerance between stamps (default 0.02)\n"
    "  --interpolate S     sample the estimate at every gt stamp, interpolating between its\n"
    "                      poses (nearest within S); for estimates at other stamps (odometry)\n"
    "Last line: ate_rmse_m=...\n";

constexpr char kRpeUsage[] =
    "usage: fusemap_eval rpe --gt A.tum --est B.tum [--delta D] [--delta-unit m|s]\n"
    "                        [--max-time-diff S]\n"
    "  --delta D           pair spacing (default 1.0)\n"
    "  --delta-unit m|s    metres travelled along the ground truth or seconds (default m)\n"
    "  --max-time-diff S   association tolerance between stamps (default 0.02)\n"
    "Last line: rpe_trans_rmse_m=... rpe_rot_mean_deg=...\n";

// Parsed `--key value` and `--flag` arguments of one subcommand.
struct Args {
  std::map<std::string, std::string> values;
  std::set<std::string> flags;
  bool help = false;
};

bool ParseArgs(int argc, char** argv, const std::set<std::string>& value_keys,
               const std::set<std::string>& flag_keys, Args* args, std::string* error) {
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      args->help = true;
    } else if (flag_keys.count(arg) > 0) {
      args->flags.insert(arg);
    } else if (value_keys.count(arg) > 0) {
      if (i + 1 >= argc) {
        *error = "option " + arg + " needs a value";
        return false;
      }
      args->values[arg] = argv[++i];
    } else {
      *error = "unknown argument '" + arg + "'";
      return false;
    }
  }
  return true;
}

bool GetRequired(const Args& args, const std::string& key, std::string* value, std::string* error) {
  const auto it = args.values.find(key);
  if (it == args.values.end()) {
    *error = "missing required option " + key;
    return false;
  }
  *value = it->second;
  return true;
}

bool GetDouble(const Args& args, const std::string& key, double* value, std::string* error) {
  const auto it = args.values.find(key);
  if (it == args.values.end()) return true;
  char* end = nullptr;
  const double parsed = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end != '\0' || !std::isfinite(parsed)) {
    *error = "option " + key + ": '" + it->second + "' is not a finite number";
    return false;
  }
  *value = parsed;
  return true;
}

// Command-line usage errors: exit 2 (bad input files exit 1).
int Fail(const std::string& error, const char* usage) {
  std::fprintf(stderr, "fusemap_eval: %s\n%s", error.c_str(), usage);
  return 2;
}

int RunRelations(int argc, char** argv) {
  Args args;
  std::string error, relations_path, trajectory_path;
  double time_offset_s = 0.0;
  double max_time_gap_s = eval::kDefaultRelationMaxTimeGapS;
  if (!ParseArgs(argc, argv,
                 {"--relations", "--trajectory", "--time-offset", "--max-time-gap", "--stamp-map"},
                 {}, &args, &error)) {
    return Fail(error, kRelationsUsage);
  }
  if (args.help) {
    std::printf("%s", kRelationsUsage);
    return 0;
  }
  if (!GetRequired(args, "--relations", &relations_path, &error) ||
      !GetRequired(args, "--trajectory", &trajectory_path, &error) ||
      !GetDouble(args, "--time-offset", &time_offset_s, &error) ||
      !GetDouble(args, "--max-time-gap", &max_time_gap_s, &error)) {
    return Fail(error, kRelationsUsage);
  }
  if (max_time_gap_s < 0.0) return Fail("--max-time-gap must be >= 0", kRelationsUsage);
  std::vector<eval::Relation> relations;
  eval::Trajectory trajectory;
  if (!io::ReadRelationsFile(relations_path, time_offset_s, &relations, &error) ||
      !io::ReadTumTrajectoryFile(trajectory_path, &trajectory, &error)) {
    std::fprintf(stderr, "fusemap_eval: %s\n", error.c_str());
    return 1;
  }
  auto stamp_map = args.values.find("--stamp-map");
  if (stamp_map != args.values.end()) {
    std::string summary;
    if (!io::MapRelationsThroughStampMapFile(stamp_map->second, &relations, &summary, &error)) {
      std::fprintf(stderr, "fusemap_eval: %s\n", error.c_str());
      return 1;
    }
    std::printf("%s\n", summary.c_str());
  }
  const eval::RelationError r = eval::EvaluateRelations(trajectory, relations, max_time_gap_s);
  std::printf("relations=%zu used=%d skipped=%d trajectory_poses=%zu\n", relations.size(),
              r.count_used, r.count_skipped, trajectory.size());
  if (r.count_used == 0) {
    std::fprintf(stderr,
                 "fusemap_eval: no relation has trajectory poses near both stamps "
                 "(check --time-offset and --max-time-gap)\n");
    return 1;
  }
  std::printf(
      "trans_sq_mean_m2=%.6g trans_sq_std_m2=%.6g rot_sq_mean_deg2=%.6g "
      "rot_sq_std_deg2=%.6g\n",
      r.trans_sq_m2.mean, r.trans_sq_m2.std, r.rot_sq_deg2.mean, r.rot_sq_deg2.std);
  std::printf("trans_mean_m=%.6g trans_std_m=%.6g rot_mean_deg=%.6g rot_std_deg=%.6g\n",
              r.trans_m.mean, r.trans_m.std, r.rot_deg.mean, r.rot_deg.std);
  return 0;
}

// --gt and --est: 2 when missing, 1 when unreadable, 0 when both were read.
int ReadPair(const Args& args, const char* usage, eval::Trajectory* gt, eval::Trajectory* est) {
  std::string gt_path, est_path, error;
  if (!GetRequired(args, "--gt", &gt_path, &error) ||
      !GetRequired(args, "--est", &est_path, &error)) {
    return Fail(error, usage);
  }
  if (!io::ReadTumTrajectoryFile(gt_path, gt, &error) ||
      !io::ReadTumTrajectoryFile(est_path, est, &error)) {
    std::fprintf(stderr, "fusemap_eval: %s\n", error.c_str());
    return 1;
  }
  return 0;
}

int RunAte(int argc, char** argv) {
  Args args;
  std::string error;
  eval::AteOptions options;
  if (!ParseArgs(argc, argv, {"--gt", "--est", "--max-time-diff", "--interpolate"},
                 {"--no-align", "--se2"}, &args, &error)) {
    return Fail(error, kAteUsage);
  }
  if (args.help) {
    std::printf("%s", kAteUsage);
    return 0;
  }
  options.align = args.flags.count("--no-align") == 0;
  options.planar = args.flags.count("--se2") > 0;
  eval::Trajectory gt, est;
  if (!GetDouble(args, "--max-time-diff", &options.max_time_diff_s, &error) ||
      !GetDouble(args, "--interpolate", &options.interpolate_max_gap_s, &error) ||
      !options.IsValid(&error)) {
    return Fail(error, kAteUsage);
  }
  if (const int status = ReadPair(args, kAteUsage, &gt, &est); status != 0) return status;
  const eval::AteResult r = eval::ComputeAte(gt, est, options);
  std::printf("gt_poses=%zu est_poses=%zu associated=%d aligned=%s\n", gt.size(), est.size(),
              r.trans_m.count, !options.align ? "no" : (options.planar ? "se2" : "se3"));
  if (r.trans_m.count == 0) {
    std::fprintf(stderr, "fusemap_eval: no estimated pose within --max-time-diff of the gt\n");
    return 1;
  }
  std::printf("T_gt_est=%s unaligned_rmse_m=%.6g\n", r.T_gt_est.DebugString().c_str(),
              r.unaligned_rmse_m);
  std::printf("ate_mean_m=%.6g ate_median_m=%.6g ate_max_m=%.6g\n", r.trans_m.mean,
              r.trans_m.median, r.trans_m.max);
  std::printf("ate_rmse_m=%.6g\n", r.trans_m.rmse);
  return 0;
}

int RunRpe(int argc, char** argv) {
  Args args;
  std::string error;
  eval::RpeOptions options;
  if (!ParseArgs(argc, argv, {"--gt", "--est", "--delta", "--delta-unit", "--max-time-diff"}, {},
                 &args, &error)) {
    return Fail(error, kRpeUsage);
  }
  if (args.help) {
    std::printf("%s", kRpeUsage);
    return 0;
  }
  const auto unit = args.values.find("--delta-unit");
  if (unit != args.values.end()) {
    if (unit->second == "m") {
      options.delta_unit = eval::DeltaUnit::kMetres;
    } else if (unit->second == "s") {
      options.delta_unit = eval::DeltaUnit::kSeconds;
    } else {
      return Fail("--delta-unit must be 'm' or 's', got '" + unit->second + "'", kRpeUsage);
    }
  }
  eval::Trajectory gt, est;
  if (!GetDouble(args, "--delta", &options.delta, &error) ||
      !GetDouble(args, "--max-time-diff", &options.max_time_diff_s, &error) ||
      !options.IsValid(&error)) {
    return Fail(error, kRpeUsage);
  }
  if (const int status = ReadPair(args, kRpeUsage, &gt, &est); status != 0) return status;
  const eval::RpeResult r = eval::ComputeRpe(gt, est, options);
  std::printf("gt_poses=%zu est_poses=%zu pairs=%d\n", gt.size(), est.size(), r.trans_m.count);
  if (r.trans_m.count == 0) {
    std::fprintf(stderr, "fusemap_eval: no pose pair spans --delta (or nothing associated)\n");
    return 1;
  }
  std::printf("rpe_trans_mean_m=%.6g rpe_trans_median_m=%.6g rpe_rot_rmse_deg=%.6g\n",
              r.trans_m.mean, r.trans_m.median, r.rot_deg.rmse);
  std::printf("rpe_trans_rmse_m=%.6g rpe_rot_mean_deg=%.6g\n", r.trans_m.rmse, r.rot_deg.mean);
  return 0;
}

}  // namespace
}  // namespace fusemap

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "%s", fusemap::kUsage);
    return 2;
  }
  const std::string command = argv[1];
  if (command == "--help" || command == "-h") {
    std::printf("%s", fusemap::kUsage);
    return 0;
  }
  if (command == "relations") return fusemap::RunRelations(argc, argv);
  if (command == "ate") return fusemap::RunAte(argc, argv);
  if (command == "rpe") return fusemap::RunRpe(argc, argv);
  std::fprintf(stderr, "fusemap_eval: unknown command '%s'\n%s", command.c_str(), fusemap::kUsage);
  return 2;
}
