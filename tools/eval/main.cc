// fusemap_eval: trajectory accuracy metrics (Kümmerle relations, ATE, RPE) over TUM files.
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "fusemap/common/command_line.h"
#include "fusemap/eval/absolute_trajectory_error.h"
#include "fusemap/eval/loop_closure_score.h"
#include "fusemap/eval/relation_error.h"
#include "fusemap/eval/relative_pose_error.h"
#include "fusemap/io/loop_tables_file.h"
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
    "  start-end  start-to-end motion of a trajectory against the ground truth's\n"
    "  loops      loop closures of a run (DIR/loops.tsv) against the ground truth\n"
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
    "usage: fusemap_eval ate --gt A.tum --est B.tum [--no-align] [--se2 [--scale]]\n"
    "                        [--max-time-diff S] [--interpolate S]\n"
    "  --no-align          do not rigidly align the estimate to the ground truth\n"
    "  --se2               align in the plane only (x, y, yaw; never mirrors the plane)\n"
    "  --scale             with --se2, also fit a uniform scale (a similarity); printed as\n"
    "                      scale= (below 1: the estimate is larger than the ground truth)\n"
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

constexpr char kStartEndUsage[] =
    "usage: fusemap_eval start-end --gt A.tum --est B.tum [--max-time-gap S]\n"
    "  The estimate's motion from its first to its last pose against the ground truth's\n"
    "  between the same stamps (a loop that did not close shows here, alignment-free).\n"
    "  --max-time-gap S   max distance from those stamps to a gt pose (default 0.05)\n"
    "Last line: start_end_m=... start_end_deg=...\n";

constexpr char kLoopsUsage[] =
    "usage: fusemap_eval loops --gt GT.tum --dir DIR [--max-error-m M] [--max-error-deg D]\n"
    "                          [--verbose]\n"
    "  Scores DIR/loops.tsv (node submap source laser_score visual_inliers decision x y yaw)\n"
    "  against the ground truth, using DIR/nodes.tum (node stamps, by index) and\n"
    "  DIR/submaps.tsv (submap first_node x y yaw). A loop is wrong when its relative pose is\n"
    "  off the truth by more than --max-error-m (default 0.3) or --max-error-deg (default 3);\n"
    "  for a laser loop held across a corridor only (loops.tsv unmeasured_x, unmeasured_y not\n"
    "  0) only the error across it counts: along it the pose is the graph's estimate, and round\n"
    "  a curved one the heading turns with it (unmeasured_turn_rad_per_m per metre along).\n"
    "  --verbose           a line per loop: node submap source decision held err_m err_deg wrong\n"
    "Prints decisions=NAME:COUNT,..., wrong_by_decision=NAME:COUNT,... and\n"
    "held_across_only=K (scored loops held across a corridor only), then, last,\n"
    "loops=N accepted=A wrong_accepted=W wrong_rejected=R unscored=U\n";

using common::CommandLine;
using common::NumberRange;

struct RelationsArgs {
  std::string relations_path, trajectory_path, stamp_map_path;
  double time_offset_s = 0.0;
  double max_time_gap_s = eval::kDefaultRelationMaxTimeGapS;
};

// Bad input files and failed runs exit 1 (usage errors exit 2 while parsing).
int Fail(const std::string& error) {
  std::fprintf(stderr, "fusemap_eval: %s\n", error.c_str());
  return 1;
}

int Relations(const RelationsArgs& args) {
  std::string error;
  std::vector<eval::Relation> relations;
  eval::Trajectory trajectory;
  if (!io::ReadRelationsFile(args.relations_path, args.time_offset_s, &relations, &error) ||
      !io::ReadTumTrajectoryFile(args.trajectory_path, &trajectory, &error)) {
    return Fail(error);
  }
  if (!args.stamp_map_path.empty()) {
    std::string summary;
    if (!io::MapRelationsThroughStampMapFile(args.stamp_map_path, &relations, &summary, &error)) {
      return Fail(error);
    }
    std::printf("%s\n", summary.c_str());
  }
  const eval::RelationError r = eval::EvaluateRelations(trajectory, relations, args.max_time_gap_s);
  std::printf("relations=%zu used=%d skipped=%d trajectory_poses=%zu\n", relations.size(),
              r.count_used, r.count_skipped, trajectory.size());
  if (r.count_used == 0) {
    return Fail("no relation has trajectory poses near both stamps "
                "(check --time-offset and --max-time-gap)");
  }
  std::printf(
      "trans_sq_mean_m2=%.6g trans_sq_std_m2=%.6g rot_sq_mean_deg2=%.6g "
      "rot_sq_std_deg2=%.6g\n",
      r.trans_sq_m2.mean, r.trans_sq_m2.std, r.rot_sq_deg2.mean, r.rot_sq_deg2.std);
  std::printf("trans_mean_m=%.6g trans_std_m=%.6g rot_mean_deg=%.6g rot_std_deg=%.6g\n",
              r.trans_m.mean, r.trans_m.std, r.rot_deg.mean, r.rot_deg.std);
  return 0;
}

int RunRelations(int argc, char** argv) {
  RelationsArgs args;
  CommandLine command_line("fusemap_eval relations", kRelationsUsage);
  command_line.AddString("--relations", &args.relations_path, CommandLine::Required::kYes);
  command_line.AddString("--trajectory", &args.trajectory_path, CommandLine::Required::kYes);
  command_line.AddDouble("--time-offset", &args.time_offset_s);
  command_line.AddDouble("--max-time-gap", &args.max_time_gap_s, NumberRange::NonNegative());
  command_line.AddString("--stamp-map", &args.stamp_map_path);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  return Relations(args);
}

// The ground truth and estimate of ate and rpe.
struct PairArgs {
  std::string gt_path, est_path;
};

void AddPairOptions(CommandLine* command_line, PairArgs* args) {
  command_line->AddString("--gt", &args->gt_path, CommandLine::Required::kYes);
  command_line->AddString("--est", &args->est_path, CommandLine::Required::kYes);
}

bool ReadPair(const PairArgs& args, eval::Trajectory* gt, eval::Trajectory* est) {
  std::string error;
  if (!io::ReadTumTrajectoryFile(args.gt_path, gt, &error) ||
      !io::ReadTumTrajectoryFile(args.est_path, est, &error)) {
    Fail(error);
    return false;
  }
  return true;
}

int Ate(const PairArgs& args, const eval::AteOptions& options) {
  eval::Trajectory gt, est;
  if (!ReadPair(args, &gt, &est)) return 1;
  const eval::AteResult r = eval::ComputeAte(gt, est, options);
  std::printf("gt_poses=%zu est_poses=%zu associated=%d aligned=%s\n", gt.size(), est.size(),
              r.trans_m.count,
              !options.align ? "no" : (options.planar ? (options.scale ? "sim2" : "se2") : "se3"));
  if (r.trans_m.count == 0) return Fail("no estimated pose within --max-time-diff of the gt");
  std::printf("T_gt_est=%s unaligned_rmse_m=%.6g\n", r.T_gt_est.DebugString().c_str(),
              r.unaligned_rmse_m);
  if (options.scale) std::printf("scale=%.6g\n", r.scale);
  std::printf("ate_mean_m=%.6g ate_median_m=%.6g ate_max_m=%.6g\n", r.trans_m.mean,
              r.trans_m.median, r.trans_m.max);
  std::printf("ate_rmse_m=%.6g\n", r.trans_m.rmse);
  return 0;
}

int RunAte(int argc, char** argv) {
  PairArgs args;
  eval::AteOptions options;
  CommandLine command_line("fusemap_eval ate", kAteUsage);
  AddPairOptions(&command_line, &args);
  command_line.AddFlag("--no-align", &options.align, false);
  command_line.AddFlag("--se2", &options.planar);
  command_line.AddFlag("--scale", &options.scale);
  command_line.AddDouble("--max-time-diff", &options.max_time_diff_s);
  command_line.AddDouble("--interpolate", &options.interpolate_max_gap_s);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  std::string error;
  if (!options.IsValid(&error)) return command_line.UsageError(error);
  return Ate(args, options);
}

int Rpe(const PairArgs& args, const eval::RpeOptions& options) {
  eval::Trajectory gt, est;
  if (!ReadPair(args, &gt, &est)) return 1;
  const eval::RpeResult r = eval::ComputeRpe(gt, est, options);
  std::printf("gt_poses=%zu est_poses=%zu pairs=%d\n", gt.size(), est.size(), r.trans_m.count);
  if (r.trans_m.count == 0) return Fail("no pose pair spans --delta (or nothing associated)");
  std::printf("rpe_trans_mean_m=%.6g rpe_trans_median_m=%.6g rpe_rot_rmse_deg=%.6g\n",
              r.trans_m.mean, r.trans_m.median, r.rot_deg.rmse);
  std::printf("rpe_trans_rmse_m=%.6g rpe_rot_mean_deg=%.6g\n", r.trans_m.rmse, r.rot_deg.mean);
  return 0;
}

int RunRpe(int argc, char** argv) {
  PairArgs args;
  eval::RpeOptions options;
  std::string unit = options.delta_unit == eval::DeltaUnit::kSeconds ? "s" : "m";
  CommandLine command_line("fusemap_eval rpe", kRpeUsage);
  AddPairOptions(&command_line, &args);
  command_line.AddDouble("--delta", &options.delta);
  command_line.AddChoice("--delta-unit", &unit, {"m", "s"});
  command_line.AddDouble("--max-time-diff", &options.max_time_diff_s);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  options.delta_unit = unit == "s" ? eval::DeltaUnit::kSeconds : eval::DeltaUnit::kMetres;
  std::string error;
  if (!options.IsValid(&error)) return command_line.UsageError(error);
  return Rpe(args, options);
}

int RunStartEnd(int argc, char** argv) {
  PairArgs args;
  double max_time_gap_s = 0.05;
  CommandLine command_line("fusemap_eval start-end", kStartEndUsage);
  AddPairOptions(&command_line, &args);
  command_line.AddDouble("--max-time-gap", &max_time_gap_s, NumberRange::NonNegative());
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  eval::Trajectory gt, est;
  if (!ReadPair(args, &gt, &est)) return 1;
  eval::StartEndError result;
  std::string error;
  if (!eval::ComputeStartEndError(gt, est, max_time_gap_s, &result, &error)) return Fail(error);
  std::printf("start_end_m=%.4f start_end_deg=%.3f\n", result.translation_m, result.rotation_deg);
  return 0;
}

// "name:count,..." or "none".
std::string CountsList(const std::map<std::string, int>& counts) {
  std::string list;
  for (const auto& [name, count] : counts) {
    list += (list.empty() ? "" : ",") + name + ":" + std::to_string(count);
  }
  return list.empty() ? "none" : list;
}

struct LoopsArgs {
  std::string gt_path, dir;
  eval::LoopScoreOptions options;
  bool verbose = false;
};

int Loops(const LoopsArgs& args) {
  std::string error;
  eval::Trajectory gt, nodes;
  std::vector<eval::LoopRecord> loops;
  std::vector<eval::SubmapAnchor> submaps;
  if (!io::ReadTumTrajectoryFile(args.gt_path, &gt, &error) ||
      !io::ReadTumTrajectoryFile(args.dir + "/nodes.tum", &nodes, &error) ||
      !io::ReadLoopsFile(args.dir + "/loops.tsv", &loops, &error) ||
      !io::ReadSubmapAnchorsFile(args.dir + "/submaps.tsv", &submaps, &error)) {
    return Fail(error);
  }
  const eval::LoopScore score = eval::ScoreLoops(loops, submaps, nodes, gt, args.options);
  if (args.verbose) {
    for (const eval::ScoredLoop& l : score.loops) {
      std::printf(
          "loop node=%d submap=%d source=%s decision=%s held=%s err_m=%.3f err_deg=%.2f "
          "wrong=%s\n",
          l.loop.node, l.loop.submap, l.loop.source.c_str(), l.loop.decision.c_str(),
          l.loop.unmeasured_direction.isZero() ? "all" : "across", l.translation_error_m,
          l.rotation_error_deg, !l.scored ? "unscored" : (l.wrong ? "yes" : "no"));
    }
  }
  std::printf("decisions=%s\n", CountsList(score.by_decision).c_str());
  std::printf("wrong_by_decision=%s\n", CountsList(score.wrong_by_decision).c_str());
  std::printf("held_across_only=%d\n", score.held_across_only);
  std::printf("loops=%zu accepted=%d wrong_accepted=%d wrong_rejected=%d unscored=%d\n",
              score.loops.size(), score.accepted, score.wrong_accepted, score.wrong_rejected,
              score.unscored);
  return 0;
}

int RunLoops(int argc, char** argv) {
  LoopsArgs args;
  CommandLine command_line("fusemap_eval loops", kLoopsUsage);
  command_line.AddString("--gt", &args.gt_path, CommandLine::Required::kYes);
  command_line.AddString("--dir", &args.dir, CommandLine::Required::kYes);
  command_line.AddDouble("--max-error-m", &args.options.max_translation_error_m,
                         NumberRange::NonNegative());
  command_line.AddDouble("--max-error-deg", &args.options.max_rotation_error_deg,
                         NumberRange::NonNegative());
  command_line.AddFlag("--verbose", &args.verbose);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  return Loops(args);
}

}  // namespace
}  // namespace fusemap

int main(int argc, char** argv) {
  return fusemap::common::RunSubcommand("fusemap_eval", fusemap::kUsage,
                                        {{"relations", fusemap::RunRelations},
                                         {"ate", fusemap::RunAte},
                                         {"rpe", fusemap::RunRpe},
                                         {"start-end", fusemap::RunStartEnd},
                                         {"loops", fusemap::RunLoops}},
                                        argc, argv);
}
