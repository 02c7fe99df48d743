// fusemap_tagscore: AprilTag detection, tag ground truth from an LCM log, trajectory scoring.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

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

// Command-line usage errors exit 2; bad input and failed runs exit 1 (Fail).
int UsageError(const std::string& message) {
  std::fprintf(stderr, "fusemap_tagscore: %s\n", message.c_str());
  return 2;
}

// Flags `--name value`; positional arguments in order. Returns false on a dangling flag.
bool ParseArgs(int argc, char** argv, const std::vector<std::string>& switches,
               std::map<std::string, std::string>* flags, std::vector<std::string>* positional,
               std::string* error) {
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) {
      positional->push_back(arg);
    } else if (std::find(switches.begin(), switches.end(), arg) != switches.end()) {
      (*flags)[arg] = "1";
    } else if (i + 1 < argc) {
      (*flags)[arg] = argv[++i];
    } else {
      *error = "flag " + arg + " needs a value";
      return false;
    }
  }
  return true;
}

bool CheckFlags(const std::map<std::string, std::string>& flags,
                const std::vector<std::string>& known, std::string* error) {
  for (const auto& [name, value] : flags) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      *error = "unknown flag " + name;
      return false;
    }
  }
  return true;
}

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

int Detect(const std::map<std::string, std::string>& flags,
           const std::vector<std::string>& images) {
  if (images.empty()) return UsageError("detect: no image given\n" + std::string(kUsage));
  ground_truth::TagDetectorOptions options;
  if (flags.count("--family")) options.family = flags.at("--family");
  if (flags.count("--refine-edges")) options.refine_edges = true;
  std::string error;
  auto detector = ground_truth::TagDetector::Create(options, &error);
  if (detector == nullptr) return Fail("detect: " + error);
  for (const std::string& path : images) {
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

int GroundTruth(const std::map<std::string, std::string>& flags) {
  for (const char* required : {"--log", "--tags", "--out"}) {
    if (!flags.count(required)) return UsageError(std::string("groundtruth: missing ") + required);
  }
  const std::string log_path = flags.at("--log");
  const std::string channel = flags.count("--channel") ? flags.at("--channel") : "RGBD";
  const std::string out_path = flags.at("--out");
  const std::string sightings_path =
      flags.count("--sightings") ? flags.at("--sightings") : out_path + ".sightings";
  ground_truth::TagGroundTruthOptions options;
  ground_truth::ScoreOptions unused;
  std::string error;
  if (flags.count("--config") && !LoadConfig(flags.at("--config"), &options, &unused, &error)) {
    return Fail(error);
  }
  ground_truth::TagMap tag_map;
  if (!io::ReadTagMapFile(flags.at("--tags"), options.default_tag_size_m, &tag_map, &error)) {
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
    std::printf("unknown tag id %d (not in %s): %d detections\n", id, flags.at("--tags").c_str(),
                n);
  }
  if (builder.trajectory().empty()) {
    return Fail(log_path + ": no frame showed a tag of " + flags.at("--tags"));
  }
  if (!io::WriteTumTrajectoryFile(out_path, builder.trajectory(), &error) ||
      !io::WriteTagSightingsFile(sightings_path, builder.sightings(), &error)) {
    return Fail(error);
  }
  std::printf("wrote %zu poses to %s and %zu sightings to %s\n", builder.trajectory().size(),
              out_path.c_str(), builder.sightings().size(), sightings_path.c_str());
  return 0;
}

int Score(const std::map<std::string, std::string>& flags) {
  for (const char* required : {"--gt", "--est", "--report"}) {
    if (!flags.count(required)) return UsageError(std::string("score: missing ") + required);
  }
  ground_truth::TagGroundTruthOptions unused;
  ground_truth::ScoreOptions options;
  std::string error;
  if (flags.count("--config") && !LoadConfig(flags.at("--config"), &unused, &options, &error)) {
    return Fail(error);
  }
  eval::Trajectory gt, est;
  if (!io::ReadTumTrajectoryFile(flags.at("--gt"), &gt, &error) ||
      !io::ReadTumTrajectoryFile(flags.at("--est"), &est, &error)) {
    return Fail(error);
  }
  if (gt.empty()) return Fail(flags.at("--gt") + ": no poses");
  if (est.empty()) return Fail(flags.at("--est") + ": no poses");
  std::vector<ground_truth::TagSighting> sightings;
  std::string sightings_path = flags.count("--sightings") ? flags.at("--sightings") : "";
  if (sightings_path.empty() && std::filesystem::exists(flags.at("--gt") + ".sightings")) {
    sightings_path = flags.at("--gt") + ".sightings";
  }
  if (!sightings_path.empty() && !io::ReadTagSightingsFile(sightings_path, &sightings, &error)) {
    return Fail(error);
  }
  std::vector<ground_truth::MapMeasure> measures;
  if (flags.count("--measures") &&
      !io::ReadMeasuresFile(flags.at("--measures"), &measures, &error)) {
    return Fail(error);
  }
  ground_truth::TrajectoryScore score;
  if (!ground_truth::ScoreTrajectory(gt, est, sightings, measures, options, &score, &error)) {
    return Fail(flags.at("--gt") + " vs " + flags.at("--est") + ": " + error);
  }
  io::ReportInfo info;
  info.gt_path = flags.at("--gt");
  info.est_path = flags.at("--est");
  if (!io::WriteScoreReport(flags.at("--report"), score, info, &error)) return Fail(error);
  for (const auto& f : io::ReportFigures(score)) {
    // Not finite: the figure does not apply (a run that never returns to its start has no
    // loop-closure error), as the HTML report says.
    if (std::isfinite(f.value)) {
      std::printf("%-40s %12.6g %s\n", f.label.c_str(), f.value, f.unit.c_str());
    } else {
      std::printf("%-40s %12s\n", f.label.c_str(), "n/a");
    }
  }
  std::printf("report: %s/index.html\n", flags.at("--report").c_str());
  return 0;
}

int Main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  std::map<std::string, std::string> flags;
  std::vector<std::string> positional;
  std::string error;
  if (!ParseArgs(argc, argv, {"--help", "--refine-edges"}, &flags, &positional, &error)) {
    return UsageError(error);
  }
  if (flags.count("--help")) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const std::map<std::string, std::vector<std::string>> known = {
      {"detect", {"--family", "--refine-edges"}},
      {"groundtruth", {"--log", "--tags", "--out", "--config", "--channel", "--sightings"}},
      {"score", {"--gt", "--est", "--report", "--config", "--sightings", "--measures"}}};
  if (!known.count(command)) return UsageError("unknown command '" + command + "'\n" + kUsage);
  if (!CheckFlags(flags, known.at(command), &error)) return UsageError(command + ": " + error);
  if (command != "detect" && !positional.empty()) {
    return UsageError(command + ": unexpected argument '" + positional[0] + "'");
  }
  if (command == "detect") return Detect(flags, positional);
  if (command == "groundtruth") return GroundTruth(flags);
  return Score(flags);
}

}  // namespace
}  // namespace fusemap

int main(int argc, char** argv) { return fusemap::Main(argc, argv); }
