#include "fusemap/io/checkpoint.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include "fusemap/pose_graph/map_builder_2d.h"
#include "testing/synthetic_room.h"
#include "byte_buffer.h"

namespace fusemap {
namespace io {
namespace {

// A real state: 40 scans of the synthetic room through MapBuilder2D, with finished submaps,
// loop-closure constraints and odometry in the extrapolator.
CheckpointContents MakeContents(bool trim) {
  pose_graph::MapBuilderOptions2D options;
  if (trim) {
    // The room is small: each new submap covers the older ones again.
    options.global_slam.overlapping_submaps_trimmer.fresh_submaps_count = 1;
    options.global_slam.overlapping_submaps_trimmer.min_added_submaps_count = 1;
  }
  options.local_slam.use_imu = false;
  options.local_slam.submaps.num_range_data = 5;
  options.global_slam.optimize_every_n_nodes = 10;
  options.global_slam.constraint_builder.max_constraint_distance_m = 3.0;
  common::InlineExecutor executor;
  pose_graph::MapBuilder2D builder(options, &executor);
  const auto walls = test_world::Room();
  for (int i = 0; i < 40; ++i) {
    const common::Rigid2d pose = test_world::ArcPose(i, 0.15);
    builder.AddOdometry({0.1 * i, pose});
    builder.AddScan(test_world::SimulateScan(walls, pose, 0.1 * i));
  }
  CheckpointContents contents;
  contents.options_yaml = "global_slam:\n  optimize_every_n_nodes: 10\n";
  contents.state = builder.ExportState();
  return contents;
}

const CheckpointContents& Contents() {
  static const CheckpointContents contents = MakeContents(false);
  return contents;
}

// Contents() with one more constraint: a copy of its last one as `edit` changes it.
CheckpointContents WithOneMoreConstraint(
    const std::function<void(pose_graph::Constraint2D*)>& edit) {
  CheckpointContents contents = Contents();
  auto& constraints = contents.state.pose_graph.constraints;
  EXPECT_FALSE(constraints.empty());
  if (constraints.empty()) return contents;
  pose_graph::Constraint2D extra = constraints.back();
  edit(&extra);
  constraints.push_back(extra);
  return contents;
}

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "fusemap_checkpoint_" + std::to_string(::getpid()) + "_" + name;
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), bytes.size());
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void RemoveAll(const std::string& path) {
  for (const char* suffix : {"", ".prev", ".tmp"}) std::remove((path + suffix).c_str());
}

// Re-seals a payload under a valid header, so that corruption reaches the state decoder.
std::string Reseal(const std::string& file, std::string payload) {
  std::string out = file.substr(0, 20);  // magic, version, flags
  ByteWriter header(&out);
  header.U64(payload.size());
  const uint32_t crc = static_cast<uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(payload.data()), payload.size()));
  header.U32(crc);
  header.U32(static_cast<uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(out.data()), 32)));
  return out + payload;
}

TEST(CheckpointTest, RoundTripIsExact) {
  const CheckpointContents& contents = Contents();
  ASSERT_GE(contents.state.submaps.size(), 4u);
  ASSERT_GT(contents.state.pose_graph.stats.loop_closures_found, 0);
  ASSERT_FALSE(contents.state.local_slam.heading_corrections_rad.empty());
  for (const bool compress : {true, false}) {
    const std::string path = TempPath(compress ? "zlib" : "raw");
    std::string error;
    ASSERT_TRUE(WriteCheckpoint(path, contents, &error, compress)) << error;
    CheckpointContents read;
    ASSERT_TRUE(ReadCheckpoint(path, &read, &error)) << error;
    EXPECT_EQ(read.fusemap_version, FusemapVersion());
    EXPECT_EQ(read.options_yaml, contents.options_yaml);
    ASSERT_EQ(read.state.submaps.size(), contents.state.submaps.size());
    for (size_t s = 0; s < read.state.submaps.size(); ++s) {
      EXPECT_EQ(read.state.submaps[s].cells, contents.state.submaps[s].cells) << s;
    }
    EXPECT_EQ(read.state.pose_graph.nodes.size(), contents.state.pose_graph.nodes.size());
    EXPECT_EQ(read.state.local_slam.heading_corrections_rad,
              contents.state.local_slam.heading_corrections_rad);
    EXPECT_EQ(read.state.pose_graph.T_map_nodes.back().angle_rad(),
              contents.state.pose_graph.T_map_nodes.back().angle_rad());
    // Every field, bit for bit: the re-encoded images are identical.
    EXPECT_EQ(EncodeCheckpoint(read, compress), EncodeCheckpoint(contents, compress));
    EXPECT_FALSE(std::ifstream(path + ".tmp").good());
    RemoveAll(path);
  }
}

TEST(CheckpointTest, TrimmedSubmapsAndNodesRoundTrip) {
  const CheckpointContents contents = MakeContents(true);
  const pose_graph::PoseGraphState2D& graph = contents.state.pose_graph;
  ASSERT_GT(graph.stats.trimmed_submaps, 0);
  ASSERT_GT(graph.stats.trimmed_nodes, 0);
  const std::string bytes = EncodeCheckpoint(contents, true);
  CheckpointContents read;
  std::string error;
  ASSERT_TRUE(DecodeCheckpoint(bytes, "ckpt", &read, &error)) << error;
  for (size_t s = 0; s < graph.submaps.size(); ++s) {
    EXPECT_EQ(read.state.pose_graph.submaps[s].trimmed, graph.submaps[s].trimmed) << s;
    EXPECT_EQ(read.state.submaps[s].cells.empty(), graph.submaps[s].trimmed) << s;
  }
  for (size_t n = 0; n < graph.nodes.size(); ++n) {
    EXPECT_EQ(read.state.pose_graph.nodes[n].trimmed, graph.nodes[n].trimmed) << n;
  }
  EXPECT_EQ(EncodeCheckpoint(read, true), bytes);
  // Smaller than the untrimmed state of the same run: the trimmed grids are not stored.
  EXPECT_LT(bytes.size(), EncodeCheckpoint(Contents(), true).size());
}

// Loop-closure candidates (waiting for verification) keep their tag; an unknown tag is an error.
TEST(CheckpointTest, LoopClosureCandidatesRoundTripAndBadTagsAreRejected) {
  const CheckpointContents contents = WithOneMoreConstraint([](pose_graph::Constraint2D* c) {
    c->tag = pose_graph::Constraint2D::kLoopClosureCandidate;
    c->T_submap_node = common::Rigid2d(0.123456789, -2.5, 0.75);
  });
  const auto& constraints = contents.state.pose_graph.constraints;
  const pose_graph::Constraint2D& candidate = constraints.back();
  const std::string bytes = EncodeCheckpoint(contents, false);
  CheckpointContents read;
  std::string error;
  ASSERT_TRUE(DecodeCheckpoint(bytes, "ckpt", &read, &error)) << error;
  ASSERT_EQ(read.state.pose_graph.constraints.size(), constraints.size());
  EXPECT_EQ(read.state.pose_graph.constraints.back().tag,
            pose_graph::Constraint2D::kLoopClosureCandidate);
  EXPECT_EQ(EncodeCheckpoint(read, false), bytes);

  // The candidate's tag byte directly follows its rotation weight.
  std::string payload = bytes.substr(36);
  std::string tail;
  ByteWriter tail_writer(&tail);
  tail_writer.F64(candidate.rotation_weight);
  tail_writer.U8(2);
  const size_t at = payload.find(tail);
  ASSERT_NE(at, std::string::npos);
  payload[at + 8] = 7;
  EXPECT_FALSE(DecodeCheckpoint(Reseal(bytes, payload), "ckpt", &read, &error));
  EXPECT_NE(error.find("tag"), std::string::npos) << error;
}

// Loop constraints keep what measured them, their id and laser score (the visual loop
// checker's decisions survive a resume); an unknown source is an error.
TEST(CheckpointTest, LoopSourcesIdsAndScoresRoundTripAndBadSourcesAreRejected) {
  CheckpointContents contents = WithOneMoreConstraint([](pose_graph::Constraint2D* c) {
    c->tag = pose_graph::Constraint2D::kInterSubmap;
    c->source = pose_graph::Constraint2D::kVisual;
    c->loop_id = 41;
    c->laser_score = 0.625;
    c->rotation_weight = 98765.4321;
  });
  const pose_graph::Constraint2D visual = contents.state.pose_graph.constraints.back();
  contents.state.pose_graph.next_loop_id = 42;
  const std::string bytes = EncodeCheckpoint(contents, false);
  CheckpointContents read;
  std::string error;
  ASSERT_TRUE(DecodeCheckpoint(bytes, "ckpt", &read, &error)) << error;
  const pose_graph::Constraint2D& back = read.state.pose_graph.constraints.back();
  EXPECT_EQ(back.source, pose_graph::Constraint2D::kVisual);
  EXPECT_EQ(back.loop_id, 41);
  EXPECT_EQ(back.laser_score, 0.625);
  EXPECT_EQ(read.state.pose_graph.next_loop_id, 42);
  EXPECT_EQ(EncodeCheckpoint(read, false), bytes);

  // The source byte follows the rotation weight and the tag byte.
  std::string payload = bytes.substr(36);
  std::string tail;
  ByteWriter tail_writer(&tail);
  tail_writer.F64(visual.rotation_weight);
  tail_writer.U8(1);
  tail_writer.U8(1);
  const size_t at = payload.find(tail);
  ASSERT_NE(at, std::string::npos);
  payload[at + 9] = 9;
  EXPECT_FALSE(DecodeCheckpoint(Reseal(bytes, payload), "ckpt", &read, &error));
  EXPECT_NE(error.find("source"), std::string::npos) << error;
}

// A corridor loop closure keeps the direction it does not measure and the turn that goes with
// it (a curved corridor); a direction that is neither zero nor a unit vector is an error.
TEST(CheckpointTest, UnmeasuredDirectionsRoundTripAndBadOnesAreRejected) {
  const CheckpointContents contents = WithOneMoreConstraint([](pose_graph::Constraint2D* c) {
    c->tag = pose_graph::Constraint2D::kInterSubmap;
    c->laser_score = 0.8125;
    c->unmeasured_direction = Eigen::Vector2d(0.6, -0.8);
    c->unmeasured_turn_rad_per_m = -0.0625;
  });
  const std::string bytes = EncodeCheckpoint(contents, false);
  CheckpointContents read;
  std::string error;
  ASSERT_TRUE(DecodeCheckpoint(bytes, "ckpt", &read, &error)) << error;
  EXPECT_EQ(read.state.pose_graph.constraints.back().unmeasured_direction,
            Eigen::Vector2d(0.6, -0.8));
  EXPECT_EQ(read.state.pose_graph.constraints.back().unmeasured_turn_rad_per_m, -0.0625);
  EXPECT_TRUE(read.state.pose_graph.constraints.front().unmeasured_direction.isZero());

  // The direction follows the laser score.
  std::string payload = bytes.substr(36);
  std::string tail;
  ByteWriter tail_writer(&tail);
  tail_writer.F64(0.8125);
  tail_writer.F64(0.6);
  const size_t at = payload.find(tail);
  ASSERT_NE(at, std::string::npos);
  std::string longer;
  ByteWriter(&longer).F64(0.9);
  payload.replace(at + 8, 8, longer);
  EXPECT_FALSE(DecodeCheckpoint(Reseal(bytes, payload), "ckpt", &read, &error));
  EXPECT_NE(error.find("unmeasured direction"), std::string::npos) << error;
}

// Node links (the camera's motion between keyframes) round-trip; a backward one is an error.
TEST(CheckpointTest, NodeLinksRoundTripAndBackwardOnesAreRejected) {
  CheckpointContents contents = Contents();
  pose_graph::NodeLink2D link;
  link.from = 1;
  link.to = 4;
  link.T_from_to = common::Rigid2d(0.7421875, -0.015625, 0.03125);
  link.translation_weight = 123456.5;
  link.rotation_weight = 9876.25;
  contents.state.pose_graph.node_links.push_back(link);
  const std::string bytes = EncodeCheckpoint(contents, false);
  CheckpointContents read;
  std::string error;
  ASSERT_TRUE(DecodeCheckpoint(bytes, "ckpt", &read, &error)) << error;
  ASSERT_EQ(read.state.pose_graph.node_links.size(), 1u);
  const pose_graph::NodeLink2D& back = read.state.pose_graph.node_links[0];
  EXPECT_EQ(back.from, 1);
  EXPECT_EQ(back.to, 4);
  EXPECT_EQ(back.T_from_to.translation(), link.T_from_to.translation());
  EXPECT_EQ(back.T_from_to.angle_rad(), link.T_from_to.angle_rad());
  EXPECT_EQ(back.translation_weight, 123456.5);
  EXPECT_EQ(back.rotation_weight, 9876.25);

  // The same link with `to` before `from`.
  std::string payload = bytes.substr(36);
  std::string pair;
  ByteWriter pair_writer(&pair);
  pair_writer.I32(1);
  pair_writer.I32(4);
  pair_writer.F64(0.7421875);
  const size_t at = payload.rfind(pair);
  ASSERT_NE(at, std::string::npos);
  std::string backward;
  ByteWriter(&backward).I32(0);
  payload.replace(at + 4, 4, backward);
  EXPECT_FALSE(DecodeCheckpoint(Reseal(bytes, payload), "ckpt", &read, &error));
  EXPECT_NE(error.find("node link"), std::string::npos) << error;
}

// The path travelled at each node and each submap's range of it (the loop-closure drift bound)
// round-trip; a path that shrinks from node to node, or a submap range that ends before it
// starts, is an error.
TEST(CheckpointTest, PathsTravelledRoundTripAndShrinkingOnesAreRejected) {
  const CheckpointContents& contents = Contents();
  const auto& nodes = contents.state.pose_graph.nodes;
  ASSERT_GE(nodes.size(), 2u);
  EXPECT_GT(nodes.back().path_m, nodes.front().path_m);
  CheckpointContents read;
  std::string error;
  ASSERT_TRUE(DecodeCheckpoint(EncodeCheckpoint(contents, false), "ckpt", &read, &error)) << error;
  EXPECT_EQ(read.state.pose_graph.nodes.back().path_m, nodes.back().path_m);
  EXPECT_EQ(read.state.pose_graph.submaps.back().last_path_m,
            contents.state.pose_graph.submaps.back().last_path_m);

  CheckpointContents shrinking = contents;
  shrinking.state.pose_graph.nodes[1].path_m = -1.0;
  EXPECT_FALSE(DecodeCheckpoint(EncodeCheckpoint(shrinking, false), "ckpt", &read, &error));
  EXPECT_NE(error.find("paths travelled"), std::string::npos) << error;
  CheckpointContents backwards = contents;
  auto& submap = backwards.state.pose_graph.submaps.front();
  submap.last_path_m = submap.first_path_m - 1.0;
  EXPECT_FALSE(DecodeCheckpoint(EncodeCheckpoint(backwards, false), "ckpt", &read, &error));
  EXPECT_NE(error.find("path range"), std::string::npos) << error;
}

TEST(CheckpointTest, ArchivedNodesOdometryAndArchiveMarkRoundTrip) {
  CheckpointContents contents = MakeContents(true);
  // What the daemon does before each save: trimmed nodes leave the graph.
  pose_graph::PoseGraphState2D& graph = contents.state.pose_graph;
  int gone = -1;
  for (size_t n = graph.nodes.size(); n-- > 0;) {
    if (!graph.nodes[n].trimmed) continue;
    gone = graph.nodes[n].index;
    graph.nodes.erase(graph.nodes.begin() + n);
    graph.T_map_nodes.erase(graph.T_map_nodes.begin() + n);
  }
  ASSERT_GE(gone, 0);
  contents.odometry = {{2.5, common::Rigid2d({1.0, 2.0}, 0.3)},
                       {2.6, common::Rigid2d({1.1, 2.0}, 0.31)}};
  contents.archive.nodes_bytes = 1234;
  contents.archive.last_odometry_stamp_s = 2.4;
  const std::string bytes = EncodeCheckpoint(contents, true);
  CheckpointContents read;
  std::string error;
  ASSERT_TRUE(DecodeCheckpoint(bytes, "ckpt", &read, &error)) << error;
  ASSERT_EQ(read.state.pose_graph.nodes.size(), graph.nodes.size());
  for (size_t n = 0; n < graph.nodes.size(); ++n) {
    EXPECT_EQ(read.state.pose_graph.nodes[n].index, graph.nodes[n].index) << n;
  }
  ASSERT_EQ(read.odometry.size(), 2u);
  EXPECT_EQ(read.odometry[1].pose.angle_rad(), 0.31);
  EXPECT_EQ(read.archive.nodes_bytes, 1234u);
  EXPECT_EQ(read.archive.last_odometry_stamp_s, 2.4);
  EXPECT_EQ(EncodeCheckpoint(read, true), bytes);

  // A constraint on a node that left the graph is an inconsistent state, not a crash later.
  CheckpointContents bad = contents;
  ASSERT_FALSE(bad.state.pose_graph.constraints.empty());
  bad.state.pose_graph.constraints.front().node = gone;
  EXPECT_FALSE(DecodeCheckpoint(EncodeCheckpoint(bad, true), "bad.fmck", &read, &error));
  EXPECT_NE(error.find("bad.fmck"), std::string::npos) << error;
  // So are node indices out of order, and odometry going back in time.
  bad = contents;
  std::swap(bad.state.pose_graph.nodes[0].index, bad.state.pose_graph.nodes[1].index);
  EXPECT_FALSE(DecodeCheckpoint(EncodeCheckpoint(bad, true), "bad.fmck", &read, &error));
  EXPECT_NE(error.find("increasing"), std::string::npos) << error;
  bad = contents;
  bad.odometry[1].stamp_s = 1.0;
  EXPECT_FALSE(DecodeCheckpoint(EncodeCheckpoint(bad, true), "bad.fmck", &read, &error));
  EXPECT_NE(error.find("back in time"), std::string::npos) << error;
}

TEST(CheckpointTest, CompressionShrinksTheGrids) {
  const size_t packed = EncodeCheckpoint(Contents(), true).size();
  const size_t raw = EncodeCheckpoint(Contents(), false).size();
  std::printf("checkpoint of %zu submaps: %zu bytes raw, %zu compressed\n",
              Contents().state.submaps.size(), raw, packed);
  EXPECT_LT(packed, raw / 2);
}

TEST(CheckpointTest, TruncatedFilesAreErrorsNamingTheFile) {
  const std::string bytes = EncodeCheckpoint(Contents(), true);
  const std::string path = TempPath("truncated");
  for (size_t length : {size_t{0}, size_t{5}, size_t{12}, size_t{20}, size_t{35}, size_t{36},
                        size_t{100}, bytes.size() / 2, bytes.size() - 1}) {
    WriteBytes(path, bytes.substr(0, length));
    CheckpointContents read;
    std::string error;
    EXPECT_FALSE(ReadCheckpoint(path, &read, &error)) << length;
    EXPECT_NE(error.find(path), std::string::npos) << error;
    if (length >= 12) {
      EXPECT_NE(error.find("truncated"), std::string::npos) << error;
    }
  }
  RemoveAll(path);
}

TEST(CheckpointTest, FlippedBytesAreChecksumErrors) {
  const std::string bytes = EncodeCheckpoint(Contents(), true);
  std::mt19937 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    std::string bad = bytes;
    const size_t at = 36 + rng() % (bytes.size() - 36);
    bad[at] = static_cast<char>(bad[at] ^ (1 << (rng() % 8)));
    CheckpointContents read;
    std::string error;
    EXPECT_FALSE(DecodeCheckpoint(bad, "ckpt", &read, &error)) << at;
    EXPECT_NE(error.find("payload checksum mismatch"), std::string::npos) << error;
  }
  std::string bad_length = bytes;
  bad_length[20] ^= 0x40;  // payload length: caught by the header checksum
  CheckpointContents read;
  std::string error;
  EXPECT_FALSE(DecodeCheckpoint(bad_length, "ckpt", &read, &error));
  EXPECT_NE(error.find("header checksum"), std::string::npos) << error;
}

TEST(CheckpointTest, BadMagicAndOtherVersionsAreNamed) {
  const std::string bytes = EncodeCheckpoint(Contents(), true);
  std::string error;
  CheckpointContents read;
  std::string bad_magic = bytes;
  bad_magic[0] = 'X';
  EXPECT_FALSE(DecodeCheckpoint(bad_magic, "ckpt", &read, &error));
  EXPECT_NE(error.find("bad magic"), std::string::npos) << error;
  std::string other_version = bytes;
  other_version[12] = static_cast<char>(kCheckpointFormatVersion + 1);
  EXPECT_FALSE(DecodeCheckpoint(other_version, "ckpt", &read, &error));
  EXPECT_NE(error.find("format version " + std::to_string(kCheckpointFormatVersion + 1)),
            std::string::npos)
      << error;
}

TEST(CheckpointTest, AtomicReplaceKeepsExactlyOnePrevious) {
  const std::string path = TempPath("rotate");
  RemoveAll(path);
  CheckpointContents contents = Contents();
  std::string error;
  for (const char* yaml : {"first", "second", "third"}) {
    contents.options_yaml = yaml;
    ASSERT_TRUE(WriteCheckpoint(path, contents, &error)) << error;
  }
  CheckpointContents read;
  ASSERT_TRUE(ReadCheckpoint(path, &read, &error)) << error;
  EXPECT_EQ(read.options_yaml, "third");
  ASSERT_TRUE(ReadCheckpoint(path + ".prev", &read, &error)) << error;
  EXPECT_EQ(read.options_yaml, "second");
  EXPECT_FALSE(std::ifstream(path + ".tmp").good());
  RemoveAll(path);
}

TEST(CheckpointTest, CorruptLatestFallsBackToPrevious) {
  const std::string path = TempPath("fallback");
  RemoveAll(path);
  CheckpointContents contents = Contents();
  std::string error, used;
  CheckpointContents read;
  EXPECT_FALSE(ReadLatestCheckpoint(path, &read, &used, &error));
  contents.options_yaml = "older";
  ASSERT_TRUE(WriteCheckpoint(path, contents, &error)) << error;
  contents.options_yaml = "newer";
  ASSERT_TRUE(WriteCheckpoint(path, contents, &error)) << error;
  ASSERT_TRUE(ReadLatestCheckpoint(path, &read, &used, &error)) << error;
  EXPECT_EQ(used, path);
  EXPECT_TRUE(error.empty());
  EXPECT_EQ(read.options_yaml, "newer");

  const std::string bytes = ReadBytes(path);
  WriteBytes(path, bytes.substr(0, bytes.size() - 10));  // as if cut off by a full disk
  ASSERT_TRUE(ReadLatestCheckpoint(path, &read, &used, &error));
  EXPECT_EQ(used, path + ".prev");
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  EXPECT_EQ(read.options_yaml, "older");

  std::remove((path + ".prev").c_str());
  EXPECT_FALSE(ReadLatestCheckpoint(path, &read, &used, &error));
  EXPECT_NE(error.find(path + ".prev"), std::string::npos) << error;
  RemoveAll(path);
}

TEST(CheckpointTest, GarbageIsRejectedWithoutCrashing) {
  const std::string valid = EncodeCheckpoint(Contents(), false);
  const std::string payload = valid.substr(36);
  // With compressed grids the structure (counts, indices) is a larger share of the bytes.
  const std::string packed = EncodeCheckpoint(Contents(), true);
  const std::string packed_payload = packed.substr(36);
  std::mt19937 rng(3);
  CheckpointContents read;
  std::string error;
  int accepted = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // Pure noise, then noise under a valid header (reaches the state decoder).
    std::string noise(rng() % 2000, '\0');
    for (char& c : noise) c = static_cast<char>(rng());
    EXPECT_FALSE(DecodeCheckpoint(noise, "noise", &read, &error));
    EXPECT_FALSE(DecodeCheckpoint(Reseal(valid, noise), "noise", &read, &error));
    // A valid payload with a few bytes changed and the checksums fixed: counts, sizes and
    // indices go wild; each must be caught (or be harmless) without crashing.
    std::string mutated = payload;
    for (int k = 0; k < 4; ++k) mutated[rng() % mutated.size()] = static_cast<char>(rng());
    if (DecodeCheckpoint(Reseal(valid, mutated), "mutated", &read, &error)) ++accepted;
    mutated = packed_payload;
    for (int k = 0; k < 2; ++k) mutated[rng() % mutated.size()] = static_cast<char>(rng());
    DecodeCheckpoint(Reseal(packed, mutated), "mutated", &read, &error);
    // Cut-off payloads under a matching header.
    EXPECT_FALSE(DecodeCheckpoint(Reseal(valid, payload.substr(0, rng() % payload.size())),
                                  "cut", &read, &error));
  }
  // Most mutations land in grid cells or poses, which stay valid values.
  std::printf("%d of 200 resealed mutations decoded\n", accepted);
  EXPECT_GT(accepted, 0);  // else Reseal itself is broken and the decoder went untested
  // The untouched payload resealed is the original file again.
  EXPECT_EQ(Reseal(valid, payload), valid);
}

}  // namespace
}  // namespace io
}  // namespace fusemap
