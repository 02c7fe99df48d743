// fusemap_tagscore: AprilTag detection, tag ground truth from an LCM log, trajectory scoring.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "fusemap/common/command_line.h"
#include "fusemap/common/config_reader.h"
#include "fusemap/ground_truth/tag_detector.h"
#include "fusemap/ground_truth/tag_ground_truth.h"
#include "fusemap/ground_truth/trajectory_score.h"
#include "fusemap/io/image_file.h"
#include "fusemap/io/lcm_log.h"
#include "fusemap/io/report_writer.h"
#include "fusemap/io/rgbd_conversions.h"
#include "fusemap/io/tag_map.h"
#include "fusemap/io/tum_trajectory.h"

namespace fusemap {
namespace {

constexpr char kUsage[] =
    "Usage:\n"
    "  fusemap_tagscore detect IMAGE... [--family tag36h11] [--refine-edges]\n"
    "      IMAGE: PNG or JPEG, at most 8192 pixels per side.\n"
    "      Prints `image id cx cy x0 y0 x1 y1 x2 y2 x3 y3` per tag (AprilTag 3 corner order:\n"
    "      counter-clockwise in the image starting bottom-left of the upright tag; pixel\n"
    "      centres at +0.5).\n"
    "  fusemap_tagscore groundtruth --log LOG.lcm --tags TAGS.yaml --out GT.tum\n"
    "      [--config CONFIG.yaml] [--channel RGBD] [--sightings FILE]\n"
    "      Robot poses from tags seen in the RGB-D frames of LOG; also writes the per-tag\n"
    "      sightings (default GT.tum.sightings) used for per-tag residuals.\n"
    "  fusemap_tagscore score --gt GT.tum --est EST.tum --report DIR [--config CONFIG.yaml]\n"
    "      [--sightings FILE] [--measures MEASURES.yaml]\n"
    "      Writes DIR/index.html and DIR/report.json (ATE with/without alignment, RPE per metre,\n"
    "      loop start-end error, per-tag residuals, map measures). GT.tum.sightings is used\n"
    "      when present and --sightings is not given.\n"
    "CONFIG: see config/tagscore.yaml (sections ground_truth and score).\n";

int Fail(const std::string& message) {
  std::fprintf(stderr, "fusemap_tagscore: %s\n", message.c_str());
  return 1;
}

using common::CommandLine;

// Reads CONFIG's ground_truth and score sections (either may be absent).
bool LoadConfig(const std::string& path, ground_truth::TagGroundTruthOptions* gt_options,
                ground_truth::ScoreOptions* score_options, std::string* error) {
  if (path.empty()) return true;
  auto reader = common::ConfigReader::FromFile(path, error);
  if (reader == nullptr) return false;
  *gt_options = ground_truth::ParseTagGroundTruthOptions(reader->Child("ground_truth"));
  *score_options = ground_truth::ParseScoreOptions(reader->Child("score"));
  return reader->Finish(error);
}

struct DetectArgs {
  std::vector<std::string> images;
  ground_truth::TagDetectorOptions options;
};

int Detect(const DetectArgs& args) {
  std::string error;
  auto detector = ground_truth::TagDetector::Create(args.options, &error);
  if (detector == nullptr) return Fail("detect: " + error);
  for (const std::string& path : args.images) {
    if (!std::filesystem::exists(path)) return Fail(path + ": no such file");
    cv::Mat mat;
    if (!io::ReadImageFile(path, cv::IMREAD_GRAYSCALE, io::kMaxImageSide, &mat, &error)) {
      return Fail(error);
    }
    ground_truth::GreyImage image;
    image.width = mat.cols;
    image.height = mat.rows;
    image.pixels.assign(mat.data, mat.data + mat.total());
    for (const auto& d : detector->Detect(image)) {
      std::printf("%s %d %.4f %.4f", path.c_str(), d.id, d.center_px.x(), d.center_px.y());
      for (const auto& c : d.corners_px) std::printf(" %.4f %.4f", c.x(), c.y());
      std::printf("\n");
    }
  }
  return 0;
}

struct GroundTruthArgs {
  std::string log_path, tags_path, out_path, config_path, sightings_path;
  std::string channel = "RGBD";
};

int GroundTruth(const GroundTruthArgs& args) {
  const std::string& log_path = args.log_path;
  const std::string& channel = args.channel;
  const std::string& out_path = args.out_path;
  const std::string sightings_path =
      args.sightings_path.empty() ? out_path + ".sightings" : args.sightings_path;
  ground_truth::TagGroundTruthOptions options;
  ground_truth::ScoreOptions unused;
  std::string error;
  if (!LoadConfig(args.config_path, &options, &unused, &error)) {
    return Fail(error);
  }
  ground_truth::TagMap tag_map;
  if (!io::ReadTagMapFile(args.tags_path, options.default_tag_size_m, &tag_map, &error)) {
    return Fail(error);
  }
  auto detector = ground_truth::TagDetector::Create(options.detector, &error);
  if (detector == nullptr) return Fail("groundtruth: " + error);
  ground_truth::TagGroundTruth builder(options, tag_map, std::move(detector));

  io::LcmLogReader reader;
  if (!reader.Open(log_path, &error)) return Fail(error);
  io::LogEvent event;
  int frames = 0, undecodable = 0, events = 0;
  while (reader.Next(&event)) {
    ++events;
    if (event.channel != channel) continue;
    sensor::RgbdFrame frame;
    if (!io::DecodeRgbdFrame(event.data.data(), static_cast<int>(event.data.size()), &frame,
                             &error)) {
      if (undecodable++ == 0) {
        std::fprintf(stderr, "%s: event %d on %s skipped: %s\n", log_path.c_str(), events,
                     channel.c_str(), error.c_str());
      }
      continue;
    }
    const auto& k = frame.color_intrinsics;
    if (!(k.fx > 0.0 && k.fy > 0.0) || k.width <= 0 || k.height <= 0) {
      return Fail(log_path + ": event " + std::to_string(events) + " on " + channel +
                  ": colour camera intrinsics missing (fx, fy or image size not positive)");
    }
    ++frames;
    builder.AddFrame(frame);
  }
  if (frames == 0) {
    return Fail(log_path + ": no decodable RGB-D frame on channel '" + channel + "' (" +
                std::to_string(events) + " events in the log)");
  }
  const auto& outcomes = builder.outcome_counts();
  auto count = [&](ground_truth::FrameOutcome o) { return outcomes.count(o) ? outcomes.at(o) : 0; };
  std::printf(
      "%s: %d frames, %d with a pose, %d without tags, %d only unknown tags, "
      "%d rejected, %d undecodable\n",
      log_path.c_str(), frames, count(ground_truth::FrameOutcome::kPose),
      count(ground_truth::FrameOutcome::kNoTag),
      count(ground_truth::FrameOutcome::kOnlyUnknownTags),
      count(ground_truth::FrameOutcome::kRejected), undecodable);
  for (const auto& [id, n] : builder.unknown_tag_counts()) {
    std::printf("unknown tag id %d (not in %s): %d detections\n", id, args.tags_path.c_str(),
                n);
  }
  if (builder.trajectory().empty()) {
    return Fail(log_path + ": no frame showed a tag of " + args.tags_path);
  }
  if (!io::WriteTumTrajectoryFile(out_path, builder.trajectory(), &error) ||
      !io::WriteTagSightingsFile(sightings_path, builder.sightings(), &error)) {
    return Fail(error);
  }
  std::printf("wrote %zu poses to %s and %zu sightings to %s\n", builder.trajectory().size(),
              out_path.c_str(), builder.sightings().size(), sightings_path.c_str());
  return 0;
}

struct ScoreArgs {
  std::string gt_path, est_path, report_dir, config_path, sightings_path, measures_path;
};

int Score(const ScoreArgs& args) {
  ground_truth::TagGroundTruthOptions unused;
  ground_truth::ScoreOptions options;
  std::string error;
  if (!LoadConfig(args.config_path, &unused, &options, &error)) {
    return Fail(error);
  }
  eval::Trajectory gt, est;
  if (!io::ReadTumTrajectoryFile(args.gt_path, &gt, &error) ||
      !io::ReadTumTrajectoryFile(args.est_path, &est, &error)) {
    return Fail(error);
  }
  if (gt.empty()) return Fail(args.gt_path + ": no poses");
  if (est.empty()) return Fail(args.est_path + ": no poses");
  std::vector<ground_truth::TagSighting> sightings;
  std::string sightings_path = args.sightings_path;
  if (sightings_path.empty() && std::filesystem::exists(args.gt_path + ".sightings")) {
    sightings_path = args.gt_path + ".sightings";
  }
  if (!sightings_path.empty() && !io::ReadTagSightingsFile(sightings_path, &sightings, &error)) {
    return Fail(error);
  }
  std::vector<ground_truth::MapMeasure> measures;
  if (!args.measures_path.empty() &&
      !io::ReadMeasuresFile(args.measures_path, &measures, &error)) {
    return Fail(error);
  }
  ground_truth::TrajectoryScore score;
  if (!ground_truth::ScoreTrajectory(gt, est, sightings, measures, options, &score, &error)) {
    return Fail(args.gt_path + " vs " + args.est_path + ": " + error);
  }
  io::ReportInfo info;
  info.gt_path = args.gt_path;
  info.est_path = args.est_path;
  if (!io::WriteScoreReport(args.report_dir, score, info, &error)) return Fail(error);
  for (const auto& f : io::ReportFigures(score)) {
    // Not finite: the figure does not apply (a run that never returns to its start has no
    // loop-closure error), as the HTML report says.
    if (std::isfinite(f.value)) {
      std::printf("%-40s %12.6g %s\n", f.label.c_str(), f.value, f.unit.c_str());
    } else {
      std::printf("%-40s %12s\n", f.label.c_str(), "n/a");
    }
  }
  std::printf("report: %s/index.html\n", args.report_dir.c_str());
  return 0;
}

int RunDetect(int argc, char** argv) {
  DetectArgs args;
  CommandLine command_line("fusemap_tagscore detect", kUsage);
  command_line.AddPositionalList("IMAGE", &args.images, 1);
  command_line.AddString("--family", &args.options.family);
  command_line.AddFlag("--refine-edges", &args.options.refine_edges);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  std::string error;
  if (!args.options.IsValid(&error)) return command_line.UsageError(error);  // --family
  return Detect(args);
}

int RunGroundTruth(int argc, char** argv) {
  GroundTruthArgs args;
  CommandLine command_line("fusemap_tagscore groundtruth", kUsage);
  command_line.AddString("--log", &args.log_path, CommandLine::Required::kYes);
  command_line.AddString("--tags", &args.tags_path, CommandLine::Required::kYes);
  command_line.AddString("--out", &args.out_path, CommandLine::Required::kYes);
  command_line.AddString("--config", &args.config_path);
  command_line.AddString("--channel", &args.channel);
  command_line.AddString("--sightings", &args.sightings_path);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  return GroundTruth(args);
}

int RunScore(int argc, char** argv) {
  ScoreArgs args;
  CommandLine command_line("fusemap_tagscore score", kUsage);
  command_line.AddString("--gt", &args.gt_path, CommandLine::Required::kYes);
  command_line.AddString("--est", &args.est_path, CommandLine::Required::kYes);
  command_line.AddString("--report", &args.report_dir, CommandLine::Required::kYes);
  command_line.AddString("--config", &args.config_path);
  command_line.AddString("--sightings", &args.sightings_path);
  command_line.AddString("--measures", &args.measures_path);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv, 2)) return *exit_code;
  return Score(args);
}

}  // namespace
}  // namespace fusemap

int main(int argc, char** argv) {
  return fusemap::common::RunSubcommand("fusemap_tagscore", fusemap::kUsage,
                                        {{"detect", fusemap::RunDetect},
                                         {"groundtruth", fusemap::RunGroundTruth},
                                         {"score", fusemap::RunScore}},
                                        argc, argv);
}
