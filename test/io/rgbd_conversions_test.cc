#include "fusemap/io/rgbd_conversions.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "fusemap_lcm/rgbd_frame_t.hpp"

namespace fusemap {
namespace io {
namespace {

sensor::RgbdFrame MakeFrame(int width, int height) {
  sensor::RgbdFrame frame;
  frame.stamp_s = 1700000000.25;
  frame.frame = "camera";
  frame.color_intrinsics = sensor::PinholeIntrinsics{width, height, 100.0, 101.0, 31.5, 23.5};
  frame.depth_intrinsics = frame.color_intrinsics;
  frame.T_color_depth = common::Rigid3d(Eigen::Vector3d(-0.025, 0, 0), Eigen::Quaterniond::Identity());
  frame.T_base_color = common::Rigid3d(Eigen::Vector3d(0.15, 0, 1.0),
                                       Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())));
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      // Smooth colour (JPEG-friendly) and arbitrary depth including 0 and the 16-bit maximum.
      frame.color_rgb.push_back(static_cast<uint8_t>(4 * u));
      frame.color_rgb.push_back(static_cast<uint8_t>(5 * v));
      frame.color_rgb.push_back(128);
      frame.depth_mm.push_back(static_cast<uint16_t>((u * 977 + v * 131) % 65536));
    }
  }
  if (frame.depth_mm.size() >= 2) {
    frame.depth_mm[0] = 0;
    frame.depth_mm[1] = 65535;
  }
  return frame;
}

TEST(RgbdConversionsTest, RoundTripJpegPng) {
  const sensor::RgbdFrame frame = MakeFrame(64, 48);
  std::vector<uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(EncodeRgbdFrame(frame, RgbdEncodeOptions(), &bytes, &error)) << error;
  sensor::RgbdFrame decoded;
  ASSERT_TRUE(DecodeRgbdFrame(bytes.data(), static_cast<int>(bytes.size()), &decoded, &error)) << error;
  EXPECT_NEAR(decoded.stamp_s, frame.stamp_s, 1e-6);
  EXPECT_EQ(decoded.frame, "camera");
  EXPECT_EQ(decoded.depth_mm, frame.depth_mm);  // PNG is lossless.
  ASSERT_EQ(decoded.color_rgb.size(), frame.color_rgb.size());
  double max_error = 0.0;
  for (size_t i = 0; i < frame.color_rgb.size(); ++i) {
    max_error = std::max(max_error, std::abs(double(decoded.color_rgb[i]) - frame.color_rgb[i]));
  }
  EXPECT_LT(max_error, 12.0);  // JPEG quality 90 on a smooth gradient.
  EXPECT_DOUBLE_EQ(decoded.color_intrinsics.fy, 101.0);
  EXPECT_LT((decoded.T_base_color.translation() - frame.T_base_color.translation()).norm(), 1e-12);
  EXPECT_LT(decoded.T_base_color.rotation().angularDistance(frame.T_base_color.rotation()), 1e-12);
  EXPECT_LT((decoded.T_color_depth.translation() - frame.T_color_depth.translation()).norm(), 1e-12);
}

TEST(RgbdConversionsTest, RoundTripRawIsExact) {
  const sensor::RgbdFrame frame = MakeFrame(20, 10);
  RgbdEncodeOptions options;
  options.color_encoding = "rgb8";
  options.depth_encoding = "mono16";
  std::vector<uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(EncodeRgbdFrame(frame, options, &bytes, &error)) << error;
  sensor::RgbdFrame decoded;
  ASSERT_TRUE(DecodeRgbdFrame(bytes.data(), static_cast<int>(bytes.size()), &decoded, &error)) << error;
  EXPECT_EQ(decoded.color_rgb, frame.color_rgb);
  EXPECT_EQ(decoded.depth_mm, frame.depth_mm);
}

TEST(RgbdConversionsTest, RejectsBadInput) {
  std::string error;
  std::vector<uint8_t> bytes;
  sensor::RgbdFrame decoded;
  // Encoding: buffers that do not match the intrinsics, or zero size.
  sensor::RgbdFrame bad = MakeFrame(16, 8);
  bad.depth_mm.pop_back();
  EXPECT_FALSE(EncodeRgbdFrame(bad, RgbdEncodeOptions(), &bytes, &error));
  EXPECT_NE(error.find("depth buffer"), std::string::npos) << error;
  EXPECT_FALSE(EncodeRgbdFrame(MakeFrame(0, 0), RgbdEncodeOptions(), &bytes, &error));

  // Truncated at every length: always rejected, never crashes.
  ASSERT_TRUE(EncodeRgbdFrame(MakeFrame(16, 8), RgbdEncodeOptions(), &bytes, &error)) << error;
  for (size_t n = 0; n < bytes.size(); n += 7) {
    EXPECT_FALSE(DecodeRgbdFrame(bytes.data(), static_cast<int>(n), &decoded, &error)) << n;
    EXPECT_FALSE(error.empty());
  }
  // Trailing garbage.
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_FALSE(DecodeRgbdFrame(longer.data(), static_cast<int>(longer.size()), &decoded, &error));
  EXPECT_NE(error.find("trailing"), std::string::npos) << error;

  // Image smaller than its intrinsics claim: encode raw 16x8 but announce 16x9.
  RgbdEncodeOptions raw;
  raw.color_encoding = "rgb8";
  sensor::RgbdFrame mismatched = MakeFrame(16, 8);
  ASSERT_TRUE(EncodeRgbdFrame(mismatched, raw, &bytes, &error)) << error;
  // The colour intrinsics' height is the int32 right after fingerprint, utime and frame string.
  const size_t height_offset = 8 + 8 + 4 + mismatched.frame.size() + 1 + 4;
  ASSERT_EQ(bytes[height_offset + 3], 8);
  bytes[height_offset + 3] = 9;
  EXPECT_FALSE(DecodeRgbdFrame(bytes.data(), static_cast<int>(bytes.size()), &decoded, &error));
  EXPECT_NE(error.find("does not match"), std::string::npos) << error;
  // Zero-size image announced.
  bytes[height_offset + 3] = 0;
  EXPECT_FALSE(DecodeRgbdFrame(bytes.data(), static_cast<int>(bytes.size()), &decoded, &error));
  EXPECT_NE(error.find("zero or absurd"), std::string::npos) << error;

  // Depth PNG of the wrong size: swap in intrinsics for a different depth size.
  sensor::RgbdFrame png_mismatch = MakeFrame(16, 8);
  ASSERT_TRUE(EncodeRgbdFrame(png_mismatch, RgbdEncodeOptions(), &bytes, &error)) << error;
  const size_t depth_width_offset = height_offset - 4 + 40;  // Second intrinsics block.
  ASSERT_EQ(bytes[depth_width_offset + 3], 16);
  bytes[depth_width_offset + 3] = 15;
  EXPECT_FALSE(DecodeRgbdFrame(bytes.data(), static_cast<int>(bytes.size()), &decoded, &error));
  EXPECT_NE(error.find("depth image declares 16x8"), std::string::npos) << error;

  // Not an rgbd_frame_t at all.
  const uint8_t junk[16] = {1, 2, 3};
  EXPECT_FALSE(DecodeRgbdFrame(junk, sizeof(junk), &decoded, &error));
  EXPECT_NE(error.find("fingerprint"), std::string::npos) << error;
}

// Re-encodes a valid frame's message after `edit` changed it (as a hostile sender could).
template <typename Edit>
std::vector<uint8_t> Edited(const sensor::RgbdFrame& frame, const RgbdEncodeOptions& options, Edit edit) {
  std::vector<uint8_t> bytes;
  std::string error;
  EXPECT_TRUE(EncodeRgbdFrame(frame, options, &bytes, &error)) << error;
  fusemap_lcm::rgbd_frame_t msg;
  EXPECT_EQ(msg.decode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  edit(&msg);
  msg.color_size = static_cast<int32_t>(msg.color_data.size());
  msg.depth_size = static_cast<int32_t>(msg.depth_data.size());
  bytes.resize(msg.getEncodedSize());
  EXPECT_GT(msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
  return bytes;
}

bool Decode(const std::vector<uint8_t>& bytes, std::string* error) {
  sensor::RgbdFrame decoded;
  return DecodeRgbdFrame(bytes.data(), static_cast<int>(bytes.size()), &decoded, error);
}

// Issue 18, item 1: cv::imdecode threw "!buf.empty()" and aborted the daemon.
TEST(RgbdConversionsTest, EmptyCompressedImagesAreRejected) {
  const sensor::RgbdFrame frame = MakeFrame(16, 8);
  std::string error;
  EXPECT_FALSE(Decode(Edited(frame, RgbdEncodeOptions(), [](auto* m) { m->color_data.clear(); }), &error));
  EXPECT_NE(error.find("colour image is empty"), std::string::npos) << error;
  EXPECT_FALSE(Decode(Edited(frame, RgbdEncodeOptions(), [](auto* m) { m->depth_data.clear(); }), &error));
  EXPECT_NE(error.find("depth image is empty"), std::string::npos) << error;
  RgbdEncodeOptions raw;
  raw.color_encoding = "rgb8";
  raw.depth_encoding = "mono16";
  EXPECT_FALSE(Decode(Edited(frame, raw, [](auto* m) { m->color_data.clear(); }), &error));
  EXPECT_FALSE(Decode(Edited(frame, raw, [](auto* m) { m->depth_data.clear(); }), &error));
}

// Finds the JPEG's SOF0 segment and overwrites the size it declares.
void SetJpegSize(std::vector<uint8_t>* jpeg, int width, int height) {
  for (size_t i = 2; i + 9 < jpeg->size(); ++i) {
    if ((*jpeg)[i] == 0xFF && (*jpeg)[i + 1] == 0xC0) {
      (*jpeg)[i + 5] = static_cast<uint8_t>(height >> 8);
      (*jpeg)[i + 6] = static_cast<uint8_t>(height & 0xff);
      (*jpeg)[i + 7] = static_cast<uint8_t>(width >> 8);
      (*jpeg)[i + 8] = static_cast<uint8_t>(width & 0xff);
      return;
    }
  }
  ADD_FAILURE() << "no SOF0 in the JPEG";
}

// Issue 18, item 2: a JPEG declaring 65500 x 65500 aborted the daemon inside OpenCV, one declaring
// 30000 x 30000 took 13 s and 2.5 GB. The declared size is now compared before decoding.
TEST(RgbdConversionsTest, HugeDeclaredImageSizesAreRejectedBeforeDecoding) {
  const sensor::RgbdFrame frame = MakeFrame(16, 8);
  std::string error;
  for (int side : {65500, 30000}) {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_FALSE(Decode(Edited(frame, RgbdEncodeOptions(),
                               [side](auto* m) { SetJpegSize(&m->color_data, side, side); }),
                        &error));
    EXPECT_NE(error.find("colour image declares " + std::to_string(side)), std::string::npos) << error;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  }
  // The depth PNG's IHDR: width at byte 16, height at 20 (big-endian).
  EXPECT_FALSE(Decode(Edited(frame, RgbdEncodeOptions(),
                             [](auto* m) {
                               m->depth_data[18] = 0xff;
                               m->depth_data[22] = 0xff;
                             }),
                      &error));
  EXPECT_NE(error.find("depth image declares"), std::string::npos) << error;
  // A colour PNG sent as "jpeg", a JPEG sent as the depth image.
  EXPECT_FALSE(Decode(Edited(frame, RgbdEncodeOptions(), [](auto* m) { m->color_data = m->depth_data; }), &error));
  EXPECT_FALSE(Decode(Edited(frame, RgbdEncodeOptions(), [](auto* m) { m->depth_data = m->color_data; }), &error));
}

// The two halves the daemon runs on different threads give the same frame as DecodeRgbdFrame.
TEST(RgbdConversionsTest, HeaderThenImagesEqualsWholeDecode) {
  const sensor::RgbdFrame frame = MakeFrame(32, 24);
  std::vector<uint8_t> bytes;
  std::string error;
  ASSERT_TRUE(EncodeRgbdFrame(frame, RgbdEncodeOptions(), &bytes, &error)) << error;
  sensor::RgbdFrame whole, split;
  RgbdImageData images;
  ASSERT_TRUE(DecodeRgbdFrame(bytes.data(), static_cast<int>(bytes.size()), &whole, &error)) << error;
  ASSERT_TRUE(DecodeRgbdFrameHeader(bytes.data(), static_cast<int>(bytes.size()), &split, &images, &error));
  EXPECT_TRUE(split.color_rgb.empty());
  EXPECT_TRUE(split.depth_mm.empty());
  ASSERT_TRUE(DecodeRgbdImages(images, &split, &error)) << error;
  EXPECT_EQ(split.color_rgb, whole.color_rgb);
  EXPECT_EQ(split.depth_mm, whole.depth_mm);
  // A body that is corrupt past a valid header fails only in the second half.
  images.color_data.resize(images.color_data.size() / 2);
  images.depth_data.resize(40);
  EXPECT_FALSE(DecodeRgbdImages(images, &split, &error));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
