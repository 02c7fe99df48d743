#include "fusemap/io/carmen_reader.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fusemap {
namespace io {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string TempPath(const std::string& name) {
  return testing::TempDir() + "/fusemap_carmen_" + std::to_string(getpid()) + "_" + name;
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::vector<CarmenRecord> ReadAll(const std::string& path, const CarmenOptions& options,
                                  CarmenSummary* summary, std::string* error) {
  CarmenReader reader(options);
  std::vector<CarmenRecord> records;
  if (!reader.Open(path, error)) return records;
  CarmenRecord record;
  while (reader.Next(&record, error)) records.push_back(record);
  *summary = reader.summary();
  return records;
}

double StampOf(const CarmenRecord& r) {
  return r.kind == CarmenRecord::Kind::kLaser ? r.scan.stamp_s : r.odometry.stamp_s;
}

// A small GMapping-style log: ODOM at scan time, FLASER, GMapping's pose echo, NEFF.
const char kGoodLog[] =
    "# message formats defined: PARAM ODOM FLASER\n"
    "PARAM robot_front_laser_max 50 nohost 0\n"
    "ODOM 0.5 0.25 0.1 0.3 -0.2 0 1.0 pippo 1.0\n"
    "FLASER 4 1.5 2.5 81.83 3.5 9 9 9 9 9 9 1.0 pippo 1.0\n"
    "ODOM 9 9 9 0 0 0 0 pippo 0\n"
    "NEFF 30\n"
    "ODOM 0.6 0.25 0.1 0.3 0 0 1.2 pippo 1.2\n"
    "FLASER 5 1 2 3 81.83 81.83 8 8 8 8 8 8 1.2 pippo 1.2\n"
    "ROBOTLASER1 0 -1.5 3.0 0.75 20 0.01 0 5 1 2 3 4 5 0"
    " 1.0877582562 2.0479425539 0.5 1 2 0.5 0 0 0 0 0 1.4 host 1.4\n";

TEST(CarmenReaderTest, ParsesGoodLines) {
  const std::string path = WriteFile("good.log", kGoodLog);
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, CarmenOptions(), &summary, &error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_EQ(records.size(), 5u);

  const CarmenRecord& odom = records[0];
  ASSERT_EQ(odom.kind, CarmenRecord::Kind::kOdometry);
  EXPECT_DOUBLE_EQ(odom.odometry.stamp_s, 1.0);
  EXPECT_DOUBLE_EQ(odom.odometry.pose.x(), 0.5);
  EXPECT_DOUBLE_EQ(odom.odometry.pose.y(), 0.25);
  EXPECT_NEAR(odom.odometry.pose.angle_rad(), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(odom.linear_velocity_mps, 0.3);
  EXPECT_DOUBLE_EQ(odom.angular_velocity_radps, -0.2);
  EXPECT_EQ(odom.line, 3);

  // Even N: [-90, +90) deg, increment pi / N.
  const CarmenRecord& scan4 = records[1];
  ASSERT_EQ(scan4.kind, CarmenRecord::Kind::kLaser);
  EXPECT_DOUBLE_EQ(scan4.scan.stamp_s, 1.0);
  EXPECT_NEAR(scan4.scan.angle_min_rad, -kPi / 2, 1e-6);
  EXPECT_NEAR(scan4.scan.angle_increment_rad, kPi / 4, 1e-6);
  EXPECT_EQ(scan4.scan.ranges_m, std::vector<float>({1.5f, 2.5f, 81.83f, 3.5f}));
  // 81.83 repeats three times: the sensor's no-return reading (ranges >= range_max_m).
  EXPECT_FLOAT_EQ(scan4.scan.range_max_m, 81.83f);
  EXPECT_EQ(summary.range_max_source, "repeated_max");

  // Odd N: [-90, +90] deg inclusive, last beam at +90.
  const CarmenRecord& scan5 = records[3];
  EXPECT_NEAR(scan5.scan.angle_increment_rad, kPi / 4, 1e-6);
  EXPECT_NEAR(scan5.scan.angle_min_rad + 4 * scan5.scan.angle_increment_rad, kPi / 2, 1e-6);

  const CarmenRecord& robot = records[4];
  ASSERT_EQ(robot.kind, CarmenRecord::Kind::kLaser);
  EXPECT_FLOAT_EQ(robot.scan.angle_min_rad, -1.5f);
  EXPECT_FLOAT_EQ(robot.scan.angle_increment_rad, 0.75f);
  EXPECT_FLOAT_EQ(robot.scan.range_max_m, 20.f);  // the line's own maximum_range
  EXPECT_EQ(robot.scan.ranges_m.size(), 5u);
  EXPECT_TRUE(robot.scan.intensities.empty());
  // Robot at (1, 2) heading 0.5 rad, laser 0.1 m ahead along that heading (10 digits printed).
  EXPECT_NEAR(robot.T_base_laser.x(), 0.1, 1e-9);
  EXPECT_NEAR(robot.T_base_laser.y(), 0.0, 1e-9);
  EXPECT_NEAR(robot.T_base_laser.angle_rad(), 0.0, 1e-9);

  EXPECT_EQ(summary.gmapping_poses_dropped, 1);
  EXPECT_EQ(summary.lasers, 3);
  EXPECT_EQ(summary.odometry, 2);
  EXPECT_EQ(summary.time_policy, "relative");
  EXPECT_EQ(summary.lines_by_type.at("NEFF"), 1);
  EXPECT_EQ(summary.lines_by_type.at("PARAM"), 1);
  EXPECT_EQ(summary.lines_by_type.at("#"), 1);
  EXPECT_EQ(summary.lines_by_type.at("ODOM"), 3);
  std::remove(path.c_str());
}

void ExpectError(const std::string& name, const std::string& text, int line,
                 const std::string& reason) {
  const std::string path = WriteFile(name, text);
  CarmenSummary summary;
  std::string error;
  ReadAll(path, CarmenOptions(), &summary, &error);
  EXPECT_NE(error.find(path + ":" + std::to_string(line) + ": "), std::string::npos) << error;
  EXPECT_NE(error.find(reason), std::string::npos) << error;
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, ReportsFileLineAndReason) {
  const std::string odom = "ODOM 0 0 0 0 0 0 1.0 pippo 1.0\n";
  ExpectError("truncated.log", odom + "FLASER 3 1 2 3 0 0 0 0 0 0 2.0 pip", 2, "truncated line");
  ExpectError("nonnumeric.log", odom + odom + "ODOM 0 x 0 0 0 0 2.0 pippo 2.0\n", 3,
              "non-numeric field 2 'x'");
  ExpectError("beams.log", odom + "FLASER 3 1 2 0 0 0 0 0 0 2.0 pippo 2.0\n", 2,
              "FLASER beam count N=3");
  ExpectError("absurd.log", odom + "FLASER 999999999 1 2\n", 2, "absurd beam count");
  ExpectError("remissions.log",
              odom + "ROBOTLASER1 0 -1 2 1 20 0 0 2 1 2 1 7 0 0 0 0 0 0 0 0 0 0 0 2 h 2\n", 2,
              "remission count 1");
}

TEST(CarmenReaderTest, SkipBadCountsAndContinues) {
  const std::string path = WriteFile(
      "skip.log",
      "ODOM 0 0 0 0 0 0 1.0 pippo 1.0\n"
      "ODOM 0 x 0 0 0 0 1.1 pippo 1.1\n"
      "FLASER 3 1 2 0 0 0 0 0 0 1.2 pippo 1.2\n"
      "ODOM 1 0 0 0 0 0 1.3 pippo 1.3\n");
  CarmenOptions options;
  options.skip_bad = true;
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, options, &summary, &error);
  EXPECT_TRUE(error.empty()) << error;
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].line, 4);
  EXPECT_EQ(summary.skipped_bad, 2);
  ASSERT_EQ(summary.first_skip_reasons.size(), 2u);
  EXPECT_NE(summary.first_skip_reasons[0].find(path + ":2: "), std::string::npos);
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, ReadsGzipTransparently) {
  const std::string path = TempPath("good.log.gz");
  gzFile gz = gzopen(path.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  ASSERT_GT(gzputs(gz, kGoodLog), 0);
  gzclose(gz);
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, CarmenOptions(), &summary, &error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_EQ(records.size(), 5u);
  EXPECT_EQ(records[1].scan.ranges_m, std::vector<float>({1.5f, 2.5f, 81.83f, 3.5f}));
  std::remove(path.c_str());
}

// Issue 18 item 13: a directory or a corrupt gzip was reported only as "cannot rewind", and a
// binary file's first "tokens" went raw into the summary's types=.
TEST(CarmenReaderTest, SaysWhyAFileCannotBeRead) {
  CarmenReader reader{CarmenOptions()};
  std::string error;
  EXPECT_FALSE(reader.Open(testing::TempDir(), &error));
  EXPECT_NE(error.find("is a directory"), std::string::npos) << error;
  EXPECT_FALSE(reader.Open(TempPath("missing.log"), &error));
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;

  const std::string gz_path = TempPath("cut.log.gz");
  gzFile gz = gzopen(gz_path.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  for (int i = 0; i < 200; ++i) ASSERT_GT(gzputs(gz, kGoodLog), 0);
  gzclose(gz);
  std::filesystem::resize_file(gz_path, std::filesystem::file_size(gz_path) / 2);
  CarmenSummary summary;
  ReadAll(gz_path, CarmenOptions(), &summary, &error);
  EXPECT_NE(error.find("gzip data"), std::string::npos) << error;
  EXPECT_EQ(error.find("rewind"), std::string::npos) << error;
  std::remove(gz_path.c_str());
}

TEST(CarmenReaderTest, NonPrintableTypesAreEscaped) {
  const std::string path = WriteFile("binary.log", std::string("\x01\xff\x7f,:ab\n") + kGoodLog);
  CarmenSummary summary;
  std::string error;
  ReadAll(path, CarmenOptions(), &summary, &error);
  ASSERT_TRUE(error.empty()) << error;
  const std::string line = summary.ToString();
  EXPECT_NE(line.find("types=\\x01\\xff\\x7f\\x2c\\x3aab:1"), std::string::npos) << line;
  for (char c : line) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << static_cast<int>(c);
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, AllZeroTimestampsAreSynthesizedFromLineOrder) {
  const std::string path = WriteFile(
      "zero.log",
      "ODOM 0 0 0 0 0 0 0 pippo 0\n"
      "FLASER 2 1 2 0 0 0 0 0 0 0 pippo 0\n"
      "ODOM 1 0 0 0.5 0 0 0 pippo 0\n"
      "FLASER 2 1 2 0 0 0 0 0 0 0 pippo 0\n");
  CarmenOptions options;
  options.synthetic_period_s = 0.25;
  options.range_max_m = 10.0;
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, options, &summary, &error);
  ASSERT_EQ(records.size(), 4u) << error;
  EXPECT_EQ(summary.time_policy, "synthesized");
  EXPECT_NE(summary.time_reason.find("zero"), std::string::npos) << summary.time_reason;
  // Each scan was taken with the ODOM line before it, so it shares that line's instant:
  // one period per instant, not per line (else the odometry is extrapolated a step too far).
  const std::vector<double> expected_s = {0.0, 0.0, 0.25, 0.25};
  for (size_t i = 0; i < records.size(); ++i) {
    EXPECT_DOUBLE_EQ(StampOf(records[i]), expected_s[i]) << "record " << i;
    EXPECT_TRUE(std::isnan(records[i].log_stamp_s)) << "no log clock to refer to";
  }
  EXPECT_FLOAT_EQ(records[1].scan.range_max_m, 10.f);
  EXPECT_EQ(summary.range_max_source, "option");
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, SaysSoWhenEveryOdomLineIsAGmappingEstimate) {
  // As in orebro: one ODOM at rest, then after each scan only GMapping's echo of its pose
  // (stamped with garbage) and, after some NEFF lines, a pose with zero time and motion a
  // metre or more from the last scan and centimetres from the next: GMapping's too, as the log
  // has no odometry stream it could belong to.
  const std::string path = WriteFile(
      "noodom.log",
      "ODOM 0 0 0 0 0 0 0 pippo 0\n"
      "FLASER 2 1 2 0.5 0 0.1 0.5 0 0.1 0 pippo 0\n"
      "ODOM 0.5 0 0.1 0 0 0 6.979 pippo 6.979\n"
      "NEFF 10\n"
      "ODOM 1.48 0.01 0.2 0 0 0 0 pippo 0\n"
      "FLASER 2 1 2 1.5 0 0.2 1.5 0 0.2 0 pippo 0\n"
      "ODOM 1.5 0 0.2 0 0 0 0 pippo 0\n");
  CarmenOptions options;
  options.range_max_m = 10.0;
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, options, &summary, &error);
  ASSERT_EQ(records.size(), 3u) << error;
  EXPECT_EQ(summary.odometry, 1);
  EXPECT_EQ(summary.gmapping_poses_dropped, 3);
  EXPECT_NE(summary.ToString().find("NO WHEEL ODOMETRY"), std::string::npos) << summary.ToString();
  std::remove(path.c_str());
}

// A freiburg-campus-shaped log: every stamp and velocity 0, a NEFF line after each scan's
// pose echo, and the wheel odometry (x = 0.1 m per reading, straight ahead) re-based after each
// scan onto GMapping's pose for that scan, as GMapping prints it.
std::string ZeroStampNeffLog(int scans, int readings_per_scan) {
  std::ostringstream log;
  log.precision(17);
  common::Rigid2d T_printed_raw;  // identity until the first scan
  int reading = 0;
  for (int s = 0; s < scans; ++s) {
    for (int i = 0; i < readings_per_scan; ++i, ++reading) {
      const common::Rigid2d printed = T_printed_raw * common::Rigid2d(0.1 * reading, 0.0, 0.0);
      log << "ODOM " << printed.translation().x() << " " << printed.translation().y() << " "
          << printed.angle_rad() << " 0 0 0 0 pippo 0\n";
    }
    // GMapping's pose for the scan, taken at the last reading: off the odometry a little.
    const common::Rigid2d raw(0.1 * (reading - 1), 0.0, 0.0);
    const common::Rigid2d gmapping(raw.translation().x() + 0.05 * (s + 1), 0.02 * (s + 1),
                                   0.01 * (s + 1));
    T_printed_raw = gmapping * raw.inverse();
    std::ostringstream pose;
    pose.precision(17);
    pose << gmapping.translation().x() << " " << gmapping.translation().y() << " "
         << gmapping.angle_rad();
    log << "FLASER 2 1 2 " << pose.str() << " " << pose.str() << " 0 pippo 0\n"
        << "ODOM " << pose.str() << " 0 0 0 0 pippo 0\n"
        << "NEFF 100\n";
  }
  return log.str();
}

TEST(CarmenReaderTest, ZeroStampsAndNeffLinesDropOnlyGmappingsPoses) {
  const int kScans = 5, kReadings = 4;
  const std::string path = WriteFile("zero_neff.log", ZeroStampNeffLog(kScans, kReadings));
  CarmenOptions options;
  options.range_max_m = 10.0;
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, options, &summary, &error);
  ASSERT_TRUE(error.empty()) << error;
  EXPECT_EQ(summary.time_policy, "synthesized");
  EXPECT_EQ(summary.lasers, kScans);
  EXPECT_EQ(summary.gmapping_poses_dropped, kScans) << summary.ToString();
  EXPECT_EQ(summary.odometry, kScans * kReadings) << summary.ToString();
  // With every re-basing undone the output is the wheel odometry itself: no step lost.
  int reading = 0;
  for (const CarmenRecord& r : records) {
    if (r.kind != CarmenRecord::Kind::kOdometry) continue;
    EXPECT_NEAR(r.odometry.pose.translation().x(), 0.1 * reading, 1e-9) << "reading " << reading;
    EXPECT_NEAR(r.odometry.pose.translation().y(), 0.0, 1e-9) << "reading " << reading;
    EXPECT_NEAR(r.odometry.pose.angle_rad(), 0.0, 1e-9) << "reading " << reading;
    ++reading;
  }
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, ScansCarryGmappingsPoseAtTheirOutputStamp) {
  const std::string path = WriteFile("reference.log", kGoodLog);
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, CarmenOptions(), &summary, &error);
  ASSERT_EQ(records.size(), 5u) << error;
  // FLASER: the x y theta right after the ranges; the record's stamp is the output stamp.
  ASSERT_TRUE(records[1].has_reference_pose);
  EXPECT_DOUBLE_EQ(records[1].reference_pose.translation().x(), 9.0);
  EXPECT_DOUBLE_EQ(records[1].reference_pose.translation().y(), 9.0);
  EXPECT_NEAR(std::cos(records[1].reference_pose.angle_rad()), std::cos(9.0), 1e-12);
  EXPECT_NEAR(std::sin(records[1].reference_pose.angle_rad()), std::sin(9.0), 1e-12);
  ASSERT_TRUE(records[3].has_reference_pose);
  EXPECT_DOUBLE_EQ(records[3].reference_pose.translation().x(), 8.0);
  EXPECT_DOUBLE_EQ(records[3].scan.stamp_s, 1.2);
  EXPECT_FALSE(records[0].has_reference_pose) << "odometry";
  EXPECT_FALSE(records[4].has_reference_pose) << "ROBOTLASER1 carries no GMapping pose";
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, KeepsFileOrderAndRepairsLateStampsSoTheyNeverDecrease) {
  // As GMapping writes them: a line stamped late (2.0) before the scan-time ODOM (1.9); the
  // poses show that file order is the true order.
  const std::string path = WriteFile(
      "order.log",
      "ODOM 0 0 0 0 0 0 1.8 pippo 1.8\n"
      "ODOM 1 0 0 0 0 0 2.0 pippo 2.0\n"
      "ODOM 2 0 0 0 0 0 1.9 pippo 1.9\n"
      "FLASER 2 1 2 0 0 0 0 0 0 1.9 pippo 1.9\n"
      "ODOM 3 0 0 0 0 0 2.1 pippo 2.1\n");
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, CarmenOptions(), &summary, &error);
  ASSERT_EQ(records.size(), 5u) << error;
  const std::vector<int> expected_lines = {1, 2, 3, 4, 5};
  for (size_t i = 0; i < records.size(); ++i) {
    EXPECT_EQ(records[i].line, expected_lines[i]);
    if (i > 0) {
      EXPECT_LE(StampOf(records[i - 1]), StampOf(records[i]));
    }
  }
  // Line 2 happened between line 1 (1.8) and line 3, which printed 1.9 to 5 significant digits
  // after the point (1.9 - 5e-6 at the earliest): midway between them.
  EXPECT_EQ(summary.repaired_stamps, 1);
  EXPECT_NEAR(StampOf(records[1]), 0.5 * (1.8 + 1.9 - 5e-6), 1e-12);
  EXPECT_DOUBLE_EQ(StampOf(records[3]), 1.9);  // the scan keeps its own stamp
  EXPECT_EQ(summary.clamped_stamps, 0);
  // What the log printed stays with each record, for ground truth on the log's clock.
  EXPECT_DOUBLE_EQ(records[1].log_stamp_s, 2.0);
  EXPECT_DOUBLE_EQ(records[2].log_stamp_s, 1.9);
  EXPECT_GT(records[1].log_stamp_resolution_s, 0.0);
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, SpreadsRecordsThatPrintTheSameRoundedStamp) {
  // GMapping prints 6 significant digits: three ODOM lines and the scan taken with the last
  // one all read 1401.34 while the robot moved. GMapping's pose echo after the scan is dropped.
  const std::string path = WriteFile(
      "spread.log",
      "ODOM 0.0 0 0 0 0 0 1401.33 pippo 1401.33\n"
      "ODOM 0.1 0 0 0 0 0 1401.34 pippo 1401.34\n"
      "ODOM 0.2 0 0 0 0 0 1401.34 pippo 1401.34\n"
      "ODOM 0.3 0 0 0 0 0 1401.34 pippo 1401.34\n"
      "FLASER 2 1 2 5 5 0 0 0 0 1401.34 pippo 1401.34\n"
      "ODOM 5 5 0 0 0 0 1401.34 pippo 1401.34\n"
      "ODOM 0.4 0 0 0 0 0 1401.35 pippo 1401.35\n");
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, CarmenOptions(), &summary, &error);
  ASSERT_EQ(records.size(), 6u) << error;
  const double step = 0.01 / 3.0;
  const std::vector<double> expected = {1401.33,
                                        1401.335 + 0.5 * step,
                                        1401.335 + 1.5 * step,
                                        1401.335 + 2.5 * step,
                                        1401.335 + 2.5 * step,  // the scan, with its ODOM
                                        1401.35};
  for (size_t i = 0; i < records.size(); ++i) {
    EXPECT_NEAR(StampOf(records[i]), expected[i], 1e-9) << "record " << i;
  }
  EXPECT_EQ(records[4].kind, CarmenRecord::Kind::kLaser);
  for (size_t i = 1; i <= 4; ++i) {
    EXPECT_DOUBLE_EQ(records[i].log_stamp_s, 1401.34) << "record " << i;
    EXPECT_DOUBLE_EQ(records[i].log_stamp_resolution_s, 0.01) << "record " << i;
  }
  EXPECT_EQ(summary.spread_stamps, 4);
  EXPECT_EQ(summary.repaired_stamps, 0);
  EXPECT_NE(summary.ToString().find("spread_stamps=4"), std::string::npos);
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, MicrosecondStampsAreNotSpreadBeyondTheirText) {
  // "%f" stamps that repeat are one instant to within 1 us.
  const std::string path = WriteFile(
      "spread_us.log",
      "ODOM 0.0 0 0 0 0 0 7.000000 pippo 7.000000\n"
      "ODOM 0.1 0 0 0 0 0 7.000000 pippo 7.000000\n"
      "ODOM 0.2 0 0 0 0 0 7.100000 pippo 7.100000\n");
  CarmenSummary summary;
  std::string error;
  const std::vector<CarmenRecord> records = ReadAll(path, CarmenOptions(), &summary, &error);
  ASSERT_EQ(records.size(), 3u) << error;
  EXPECT_NEAR(StampOf(records[0]), 7.0 - 0.25e-6, 1e-12);
  EXPECT_NEAR(StampOf(records[1]), 7.0 + 0.25e-6, 1e-12);
  EXPECT_DOUBLE_EQ(StampOf(records[2]), 7.1);
  EXPECT_EQ(summary.spread_stamps, 2);
  std::remove(path.c_str());
}

TEST(CarmenReaderTest, IntelLogIfPresent) {
  const std::string path = std::string(FUSEMAP_SHARED_DATA_DIR) + "/laser2d/intel.gfs.log";
  if (!std::ifstream(path).good()) GTEST_SKIP() << "shared data not found: " << path;
  CarmenReader reader{CarmenOptions()};
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error)) << error;
  CarmenRecord record;
  double last_s = -1.0;
  int backward = 0;
  while (reader.Next(&record, &error)) {
    if (StampOf(record) < last_s) ++backward;
    last_s = StampOf(record);
  }
  ASSERT_TRUE(error.empty()) << error;
  EXPECT_EQ(backward, 0);
  EXPECT_EQ(reader.summary().lasers, 910);
  EXPECT_EQ(reader.summary().odometry, 14541 - 910);
  EXPECT_EQ(reader.summary().time_policy, "relative");
  EXPECT_NEAR(reader.summary().range_max_m, 81.83, 1e-4);
  // The last line's own stamp: file order is kept and only late stamps are lowered.
  EXPECT_NEAR(last_s, 2691.29, 1e-6);
  EXPECT_EQ(reader.summary().odometry_rebases_undone, 910);
}

}  // namespace
}  // namespace io
}  // namespace fusemap
