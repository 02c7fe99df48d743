// fusemap_bench_vloop: what the visual loop checker costs on one core at 640x480 — keyframe
// processing (ORB + BoW, retrieval, PnP verification), retrieval among N keyframes, a motion
// link's refinement on pixels, vocabulary load time and memory per keyframe. Real frames from
// ../shared/data/visual; the N database entries are synthesised from those frames' descriptors.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "fusemap/common/command_line.h"
#include "fusemap/common/math.h"
#include "fusemap/visual_loop/geometric_verifier.h"
#include "fusemap/visual_loop/keyframe.h"
#include "fusemap/visual_loop/keyframe_database.h"
#include "fusemap/visual_loop/patch_alignment.h"
#include "fusemap/visual_loop/vocabulary.h"

namespace {

using namespace fusemap;
using common::Percentile;
using Clock = std::chrono::steady_clock;

constexpr char kUsage[] =
    "usage: fusemap_bench_vloop [--data DIR] [--vocabulary V] [--keyframes N] [--rounds R]\n"
    "Times the visual loop checker on one core: keyframe processing (ORB + BoW, retrieval among\n"
    "N keyframes, PnP verification of one candidate) over R rounds of the RGB-D frames in DIR\n"
    "(default ../shared/data/visual: ICL living room and TUM pair), retrieval alone, a motion\n"
    "link's refinement on pixels (each pair is two consecutive frames), vocabulary load, bytes\n"
    "per keyframe. Defaults N=10000, R=20. Times are this thread's CPU time (the\n"
    "cost on one core, whatever else runs); the keyframe line also gives wall time.\n"
    "Exit 1 if the data cannot be read.\n";

double Ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// CPU time of this thread in ms: on a shared machine wall time also counts other processes'
// slices, while the cost on one core is what the checker's thread will need.
double ThreadCpuMs() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

struct Frame {
  cv::Mat image;
  cv::Mat depth_m;
  sensor::PinholeIntrinsics intrinsics;
};

struct Pair {
  Frame a;  // with depth: the stored keyframe
  Frame b;  // the query
};

bool ReadPair(const std::string& a, const std::string& da, const std::string& b, double scale,
              const sensor::PinholeIntrinsics& in, std::vector<Pair>* pairs) {
  Pair pair;
  pair.a.image = cv::imread(a, cv::IMREAD_COLOR);
  pair.b.image = cv::imread(b, cv::IMREAD_COLOR);
  const cv::Mat depth = cv::imread(da, cv::IMREAD_ANYDEPTH);
  if (pair.a.image.empty() || pair.b.image.empty() || depth.type() != CV_16UC1) {
    std::fprintf(stderr, "error: cannot read %s / %s / %s\n", a.c_str(), da.c_str(), b.c_str());
    return false;
  }
  pair.a.depth_m = visual_loop::DepthToMeters(depth, scale);
  pair.a.intrinsics = pair.b.intrinsics = in;
  pairs->push_back(pair);
  return true;
}

sensor::PinholeIntrinsics Intrinsics(double fx, double fy, double cx, double cy) {
  sensor::PinholeIntrinsics in;
  in.width = 640;
  in.height = 480;
  in.fx = fx;
  in.fy = fy;
  in.cx = cx;
  in.cy = cy;
  return in;
}

struct Args {
  std::string data = FUSEMAP_DEFAULT_VISUAL_DATA;
  std::string vocabulary_path = FUSEMAP_DEFAULT_VOCABULARY;
  int num_keyframes = 10000;
  int rounds = 20;
};

// Times the checker and prints the figures: 0, or 1 if the data cannot be read.
int Benchmark(const Args& args) {
  const std::string& data = args.data;
  const int num_keyframes = args.num_keyframes;
  const int rounds = args.rounds;
  cv::setNumThreads(1);  // one core, as the checker's own thread will have

  auto start = Clock::now();
  std::string error;
  const std::optional<visual_loop::Vocabulary> vocabulary =
      visual_loop::Vocabulary::Load(args.vocabulary_path, &error);
  const double load_ms = Ms(start);
  if (!vocabulary) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return 1;
  }

  std::vector<Pair> pairs;
  const std::string icl = data + "/open3d_icl_livingroom";
  const std::string tum = data + "/slambook2_tum_fr2/pair_ch7";
  for (int j = 1; j < 5; ++j) {
    if (!ReadPair(icl + "/color/0000" + std::to_string(j - 1) + ".jpg", icl + "/depth/0000" + std::to_string(j - 1) + ".png",
                  icl + "/color/0000" + std::to_string(j) + ".jpg", 1000.0, Intrinsics(525, 525, 319.5, 239.5), &pairs)) {
      return 1;
    }
  }
  if (!ReadPair(tum + "/1.png", tum + "/1_depth.png", tum + "/2.png", 5000.0,
                Intrinsics(520.9, 521.0, 325.1, 249.7), &pairs)) {
    return 1;
  }

  const visual_loop::OrbExtractor extractor{visual_loop::OrbOptions{}};
  const visual_loop::VerificationOptions verification;
  std::vector<visual_loop::Keyframe> stored;
  std::vector<visual_loop::CameraImage> stored_images;  // what the checker holds of its latest
  cv::Mat pool;  // every real descriptor: the material for synthetic keyframes
  for (const Pair& pair : pairs) {
    visual_loop::CameraImage image;
    cv::cvtColor(pair.a.image, image.gray, cv::COLOR_BGR2GRAY);
    image.depth_m = pair.a.depth_m;
    image.intrinsics = pair.a.intrinsics;
    stored_images.push_back(image);
    stored.push_back(visual_loop::MakeKeyframe(pair.a.image, pair.a.depth_m, pair.a.intrinsics, extractor,
                                               &*vocabulary, visual_loop::KeyframeOptions{}));
    pool.push_back(stored.back().descriptors);
  }

  // Synthetic keyframes: 1000 descriptors drawn from the real pool with a few bits flipped each,
  // so the words they hit follow the real images' word frequencies.
  start = Clock::now();
  std::mt19937 rng(1);
  visual_loop::KeyframeDatabase database(vocabulary->num_words());
  size_t postings = 0;
  for (int id = 0; id < num_keyframes; ++id) {
    cv::Mat descriptors(1000, 32, CV_8UC1);
    for (int r = 0; r < descriptors.rows; ++r) {
      pool.row(static_cast<int>(rng() % pool.rows)).copyTo(descriptors.row(r));
      for (int flip = 0; flip < 8; ++flip) {
        const int bit = static_cast<int>(rng() % 256);
        descriptors.at<uint8_t>(r, bit / 8) ^= static_cast<uint8_t>(1 << (bit % 8));
      }
    }
    const visual_loop::BowVector bow = vocabulary->Transform(descriptors);
    postings += bow.size();
    database.Add(id, bow);
  }
  const double synth_s = Ms(start) / 1000.0;

  std::vector<double> extract_ms, retrieve_ms, verify_ms, total_ms, wall_ms, match_ms, refine_ms;
  int verified = 0;
  int aligned_points = 0;
  int inliers = 0;
  for (int round = 0; round < rounds; ++round) {
    for (size_t p = 0; p < pairs.size(); ++p) {
      const Frame& query = pairs[p].b;
      const auto wall0 = Clock::now();
      const double t0 = ThreadCpuMs();
      const visual_loop::Keyframe keyframe = visual_loop::MakeKeyframe(
          query.image, cv::Mat(), query.intrinsics, extractor, &*vocabulary, visual_loop::KeyframeOptions{});
      const double t1 = ThreadCpuMs();
      const std::vector<visual_loop::DatabaseResult> results = database.Query(keyframe.bow, num_keyframes, 50);
      const double t2 = ThreadCpuMs();
      const visual_loop::VerificationResult result = visual_loop::VerifyKeyframes(stored[p], keyframe, verification);
      const double t3 = ThreadCpuMs();
      wall_ms.push_back(Ms(wall0));
      visual_loop::MatchDescriptors(stored[p].descriptors, keyframe.descriptors, verification.matching,
                                    &stored[p].vocabulary_nodes, &keyframe.vocabulary_nodes);
      match_ms.push_back(ThreadCpuMs() - t3);
      // Each pair is two consecutive frames, as a motion link is: its refinement on pixels
      // (the query's grey image, then RefineByPatchAlignment) comes on top of the keyframe.
      const double t4 = ThreadCpuMs();
      visual_loop::CameraImage query_image;
      cv::cvtColor(query.image, query_image.gray, cv::COLOR_BGR2GRAY);
      query_image.intrinsics = query.intrinsics;
      visual_loop::VerificationResult refined = result;
      const int aligned =
          visual_loop::RefineByPatchAlignment(stored[p], stored_images[p], keyframe, query_image,
                                              visual_loop::PatchAlignmentOptions{}, &refined);
      refine_ms.push_back(ThreadCpuMs() - t4);
      aligned_points += aligned;
      inliers += result.inliers;
      verified += result.verified ? 1 : 0;
      extract_ms.push_back(t1 - t0);
      retrieve_ms.push_back(t2 - t1);
      verify_ms.push_back(t3 - t2);
      total_ms.push_back(t3 - t0);
      if (results.empty()) std::fprintf(stderr, "warning: empty retrieval\n");
    }
  }
  size_t bytes = 0;
  for (const auto& k : stored) bytes += k.BytesUsed();
  const size_t bytes_per_keyframe = bytes / stored.size();
  const size_t index_bytes_per_keyframe = postings * 8 / num_keyframes;  // (id, weight) per word

  std::printf("frames=%zu rounds=%d verified=%d/%zu database_keyframes=%d synthesis_s=%.1f\n",
              pairs.size(), rounds, verified, total_ms.size(), num_keyframes, synth_s);
  std::printf("features_bow_ms median=%.2f p99=%.2f\n", Percentile(extract_ms, 0.5), Percentile(extract_ms, 0.99));
  std::printf("retrieval_ms keyframes=%d median=%.2f p99=%.2f\n", num_keyframes, Percentile(retrieve_ms, 0.5),
              Percentile(retrieve_ms, 0.99));
  std::printf("verification_ms median=%.2f p99=%.2f (of which descriptor matching median=%.2f)\n",
              Percentile(verify_ms, 0.5), Percentile(verify_ms, 0.99), Percentile(match_ms, 0.5));
  std::printf("keyframe_ms median=%.2f p99=%.2f (thread CPU time; wall median=%.2f p99=%.2f)\n",
              Percentile(total_ms, 0.5), Percentile(total_ms, 0.99), Percentile(wall_ms, 0.5),
              Percentile(wall_ms, 0.99));
  std::printf("motion_link_refinement_ms median=%.2f p99=%.2f aligned=%d/%d inliers\n",
              Percentile(refine_ms, 0.5), Percentile(refine_ms, 0.99), aligned_points, inliers);
  std::printf("vocabulary_load_ms=%.1f words=%d\n", load_ms, vocabulary->num_words());
  std::printf("bytes_per_keyframe=%zu index_bytes_per_keyframe=%zu\n", bytes_per_keyframe, index_bytes_per_keyframe);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  const int kMaxInt = std::numeric_limits<int>::max();
  fusemap::common::CommandLine command_line("fusemap_bench_vloop", kUsage);
  command_line.AddString("--data", &args.data);
  command_line.AddString("--vocabulary", &args.vocabulary_path);
  command_line.AddInt("--keyframes", &args.num_keyframes, 1, kMaxInt);
  command_line.AddInt("--rounds", &args.rounds, 1, kMaxInt);
  if (const auto exit_code = command_line.ParseOrExitCode(argc, argv)) return *exit_code;
  return Benchmark(args);
}
