#include "fusemap/pose_graph/loop_closure_verifier_2d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "fusemap/common/math.h"

namespace fusemap {
namespace pose_graph {
namespace {

// A robot drives along x at 0.5 m per node; local SLAM has drifted by a fixed T_drift between
// the time the submaps were built and the revisit, so T_local_node = T_drift * true pose.
common::Rigid2d TruePose(int node) { return common::Rigid2d(0.5 * node, 0.1 * node, 0.02 * node); }

const common::Rigid2d kDrift(1.5, -0.7, 0.3);

common::Rigid2d TrueSubmapPose(int submap) { return common::Rigid2d(4.0 * submap, 0.0, 0.1); }

// A closure of revisit node `node` in submap `submap`, matched with `match_error` applied.
ClosureView2D Closure(int node, int submap,
                      const common::Rigid2d& match_error = common::Rigid2d::Identity()) {
  ClosureView2D view;
  view.node = node;
  view.submap = submap;
  view.T_local_submap = TrueSubmapPose(submap);  // built before the drift
  view.T_local_node = kDrift * TruePose(node);
  view.T_submap_node = TrueSubmapPose(submap).inverse() * TruePose(node) * match_error;
  return view;
}

LoopClosureVerificationOptions2D Options(int min_agreeing) {
  LoopClosureVerificationOptions2D options;
  options.min_agreeing_closures = min_agreeing;
  return options;
}

TEST(LoopClosureVerifier2DTest, RightClosuresAgreeDespiteDrift) {
  const auto options = Options(1);
  EXPECT_TRUE(ClosuresAgree(Closure(10, 0), Closure(12, 0), options));
  // Different submaps: their relative pose comes from local SLAM too.
  EXPECT_TRUE(ClosuresAgree(Closure(10, 0), Closure(15, 1), options));
  // Small matching noise is tolerated.
  EXPECT_TRUE(ClosuresAgree(Closure(10, 0, common::Rigid2d(0.1, 0.05, 0.02)), Closure(11, 1),
                            options));
}

TEST(LoopClosureVerifier2DTest, WrongClosureDisagrees) {
  const auto options = Options(1);
  // Matched one door further along a corridor, or turned by a few degrees.
  EXPECT_FALSE(ClosuresAgree(Closure(10, 0, common::Rigid2d(1.0, 0.0, 0.0)), Closure(12, 0),
                             options));
  EXPECT_FALSE(ClosuresAgree(Closure(10, 0, common::Rigid2d(0.0, 0.0, 0.1)), Closure(12, 0),
                             options));
  EXPECT_FALSE(ClosuresAgree(Closure(10, 0), Closure(12, 0, common::Rigid2d(0.0, -0.4, 0.0)),
                             options));
}

TEST(LoopClosureVerifier2DTest, SameNodeAndDistantNodesAreNotCompared) {
  auto options = Options(1);
  EXPECT_FALSE(ClosuresAgree(Closure(10, 0), Closure(10, 1), options));
  options.max_node_gap = 5;
  EXPECT_TRUE(ClosuresAgree(Closure(10, 0), Closure(15, 0), options));
  EXPECT_FALSE(ClosuresAgree(Closure(10, 0), Closure(16, 0), options));
}

TEST(LoopClosureVerifier2DTest, AcceptsOnceEnoughAgreeAndNeverTheOddOneOut) {
  const auto options = Options(2);
  std::vector<ClosureView2D> closures;
  closures.push_back(Closure(20, 0));
  EXPECT_TRUE(ClosuresToAccept(closures, 0, options).empty());
  closures.push_back(Closure(21, 0, common::Rigid2d(1.2, 0.0, 0.0)));  // wrong
  EXPECT_TRUE(ClosuresToAccept(closures, 1, options).empty());
  closures.push_back(Closure(22, 1));
  EXPECT_TRUE(ClosuresToAccept(closures, 2, options).empty());  // 20 and 22: one partner each
  closures.push_back(Closure(24, 1));
  std::vector<int> accept = ClosuresToAccept(closures, 3, options);
  std::sort(accept.begin(), accept.end());
  EXPECT_EQ(accept, (std::vector<int>{0, 2, 3}));
  for (int i : accept) closures[i].accepted = true;
  // A later right closure agrees with accepted ones and is accepted alone.
  closures.push_back(Closure(25, 1));
  EXPECT_EQ(ClosuresToAccept(closures, 4, options), (std::vector<int>{4}));
  closures[4].accepted = true;
  // The wrong one still has no partner.
  closures.push_back(Closure(26, 0, common::Rigid2d(0.0, 0.0, -0.2)));
  EXPECT_TRUE(ClosuresToAccept(closures, 5, options).empty());
}

TEST(LoopClosureVerifier2DTest, AcceptedSetDoesNotDependOnArrivalOrder) {
  const auto options = Options(2);
  std::vector<ClosureView2D> all;
  for (int node = 30; node < 42; ++node) {
    // Every third match is off by a different wrong offset.
    const common::Rigid2d error =
        node % 3 == 0 ? common::Rigid2d(0.3 * (node - 28), 0.2, 0.05 * (node % 4)) :
                        common::Rigid2d::Identity();
    all.push_back(Closure(node, node % 2, error));
  }
  std::vector<bool> reference;
  std::mt19937 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<int> order(all.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    if (trial > 0) std::shuffle(order.begin(), order.end(), rng);
    std::vector<ClosureView2D> arrived;
    std::vector<int> original;
    for (int i : order) {
      arrived.push_back(all[i]);
      original.push_back(i);
      for (int a : ClosuresToAccept(arrived, static_cast<int>(arrived.size()) - 1, options)) {
        arrived[a].accepted = true;
      }
    }
    std::vector<bool> accepted(all.size(), false);
    for (size_t k = 0; k < arrived.size(); ++k) accepted[original[k]] = arrived[k].accepted;
    if (trial == 0) {
      reference = accepted;
      for (size_t i = 0; i < all.size(); ++i) {
        EXPECT_EQ(accepted[i], all[i].node % 3 != 0) << "node " << all[i].node;
      }
    } else {
      EXPECT_EQ(accepted, reference) << "trial " << trial;
    }
  }
}

TEST(LoopClosureVerifier2DTest, OptionsParseAndValidate) {
  LoopClosureVerificationOptions2D defaults;
  EXPECT_FALSE(defaults.enabled());
  std::string error;
  EXPECT_TRUE(defaults.IsValid(&error));
  auto reader = common::ConfigReader::FromString(
      "{min_agreeing_closures: 2, max_node_gap: 20, max_translation_error_m: 0.5, "
      "max_rotation_error_rad: 0.1}",
      "test", &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto options = ParseLoopClosureVerificationOptions2D(*reader);
  EXPECT_TRUE(reader->Finish(&error)) << error;
  EXPECT_TRUE(options.enabled());
  EXPECT_EQ(options.min_agreeing_closures, 2);
  EXPECT_EQ(options.max_node_gap, 20);
  EXPECT_EQ(options.max_translation_error_m, 0.5);
  EXPECT_EQ(options.max_rotation_error_rad, 0.1);
  auto bad = common::ConfigReader::FromString("{max_translation_error_m: 0}", "bad.yaml", &error);
  ASSERT_NE(bad, nullptr) << error;
  ParseLoopClosureVerificationOptions2D(*bad);
  EXPECT_FALSE(bad->Finish(&error));
  EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
  auto unknown = common::ConfigReader::FromString("{min_agreeing: 2}", "unknown.yaml", &error);
  ASSERT_NE(unknown, nullptr) << error;
  ParseLoopClosureVerificationOptions2D(*unknown);
  EXPECT_FALSE(unknown->Finish(&error));
}

}  // namespace
}  // namespace pose_graph
}  // namespace fusemap
