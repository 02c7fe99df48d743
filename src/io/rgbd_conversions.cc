#include "fusemap/io/rgbd_conversions.h"

#include <cmath>
#include <cstring>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "fusemap/io/lcm_conversions.h"
#include "fusemap_lcm/rgbd_frame_t.hpp"
#include "image_header.h"
#include "lcm_wire.h"

namespace fusemap {
namespace io {
namespace {

bool Fail(const std::string& reason, std::string* error) {
  *error = reason;
  return false;
}

void ToLcm(const sensor::PinholeIntrinsics& k, fusemap_lcm::camera_intrinsics_t* msg) {
  msg->width = k.width;
  msg->height = k.height;
  msg->fx = k.fx;
  msg->fy = k.fy;
  msg->cx = k.cx;
  msg->cy = k.cy;
}

bool FromLcm(const fusemap_lcm::camera_intrinsics_t& msg, const char* name,
             sensor::PinholeIntrinsics* k, std::string* error) {
  if (msg.width <= 0 || msg.height <= 0 || msg.width > kMaxImageSide || msg.height > kMaxImageSide) {
    return Fail(std::string(name) + " size " + std::to_string(msg.width) + "x" +
                    std::to_string(msg.height) + " is zero or absurd",
                error);
  }
  if (!std::isfinite(msg.fx) || !std::isfinite(msg.fy) || !std::isfinite(msg.cx) ||
      !std::isfinite(msg.cy) || msg.fx <= 0.0 || msg.fy <= 0.0) {
    return Fail(std::string(name) + " focal lengths must be finite and positive", error);
  }
  *k = sensor::PinholeIntrinsics{msg.width, msg.height, msg.fx, msg.fy, msg.cx, msg.cy};
  return true;
}

void ToLcm(const common::Rigid3d& T, fusemap_lcm::rigid_transform_t* msg) {
  for (int i = 0; i < 3; ++i) msg->translation[i] = T.translation()[i];
  msg->rotation[0] = T.rotation().w();
  msg->rotation[1] = T.rotation().x();
  msg->rotation[2] = T.rotation().y();
  msg->rotation[3] = T.rotation().z();
}

bool FromLcm(const fusemap_lcm::rigid_transform_t& msg, const char* name, common::Rigid3d* T,
             std::string* error) {
  double norm2 = 0.0;
  for (double v : msg.translation) {
    if (!std::isfinite(v)) return Fail(std::string(name) + " translation is not finite", error);
  }
  for (double v : msg.rotation) {
    if (!std::isfinite(v)) return Fail(std::string(name) + " rotation is not finite", error);
    norm2 += v * v;
  }
  if (std::abs(norm2 - 1.0) > 1e-3) return Fail(std::string(name) + " rotation is not a unit quaternion", error);
  *T = common::Rigid3d(Eigen::Vector3d(msg.translation[0], msg.translation[1], msg.translation[2]),
                       Eigen::Quaterniond(msg.rotation[0], msg.rotation[1], msg.rotation[2], msg.rotation[3]));
  return true;
}

size_t PixelCount(const sensor::PinholeIntrinsics& k) {
  return static_cast<size_t>(k.width) * static_cast<size_t>(k.height);
}

}  // namespace

bool RgbdEncodeOptions::IsValid(std::string* error) const {
  if (color_encoding != "jpeg" && color_encoding != "rgb8") return Fail("color_encoding must be jpeg or rgb8", error);
  if (depth_encoding != "png16" && depth_encoding != "mono16") return Fail("depth_encoding must be png16 or mono16", error);
  if (jpeg_quality < 1 || jpeg_quality > 100) return Fail("jpeg_quality must be in [1, 100]", error);
  if (png_compression < 0 || png_compression > 9) return Fail("png_compression must be in [0, 9]", error);
  return true;
}

bool EncodeRgbdFrame(const sensor::RgbdFrame& frame, const RgbdEncodeOptions& options,
                     std::vector<uint8_t>* bytes, std::string* error) {
  if (!options.IsValid(error)) return false;
  const sensor::PinholeIntrinsics& kc = frame.color_intrinsics;
  const sensor::PinholeIntrinsics& kd = frame.depth_intrinsics;
  if (kc.width <= 0 || kc.height <= 0 || frame.color_rgb.size() != 3 * PixelCount(kc)) {
    return Fail("colour buffer does not match its intrinsics", error);
  }
  if (kd.width <= 0 || kd.height <= 0 || frame.depth_mm.size() != PixelCount(kd)) {
    return Fail("depth buffer does not match its intrinsics", error);
  }
  fusemap_lcm::rgbd_frame_t msg;
  msg.utime = StampToUtime(frame.stamp_s);
  msg.frame = frame.frame;
  ToLcm(kc, &msg.color_intrinsics);
  ToLcm(kd, &msg.depth_intrinsics);
  ToLcm(frame.T_color_depth, &msg.T_color_depth);
  ToLcm(frame.T_base_color, &msg.T_base_color);
  msg.color_encoding = options.color_encoding;
  if (options.color_encoding == "jpeg") {
    const cv::Mat rgb(kc.height, kc.width, CV_8UC3, const_cast<uint8_t*>(frame.color_rgb.data()));
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    if (!cv::imencode(".jpg", bgr, msg.color_data, {cv::IMWRITE_JPEG_QUALITY, options.jpeg_quality})) {
      return Fail("JPEG encoding failed", error);
    }
  } else {
    msg.color_data = frame.color_rgb;
  }
  msg.depth_encoding = options.depth_encoding;
  if (options.depth_encoding == "png16") {
    const cv::Mat depth(kd.height, kd.width, CV_16UC1, const_cast<uint16_t*>(frame.depth_mm.data()));
    if (!cv::imencode(".png", depth, msg.depth_data, {cv::IMWRITE_PNG_COMPRESSION, options.png_compression})) {
      return Fail("PNG encoding failed", error);
    }
  } else {
    msg.depth_data.resize(2 * frame.depth_mm.size());
    for (size_t i = 0; i < frame.depth_mm.size(); ++i) {
      msg.depth_data[2 * i] = static_cast<uint8_t>(frame.depth_mm[i] & 0xff);
      msg.depth_data[2 * i + 1] = static_cast<uint8_t>(frame.depth_mm[i] >> 8);
    }
  }
  msg.color_size = static_cast<int32_t>(msg.color_data.size());
  msg.depth_size = static_cast<int32_t>(msg.depth_data.size());
  bytes->resize(msg.getEncodedSize());
  if (msg.encode(bytes->data(), 0, static_cast<int>(bytes->size())) < 0) return Fail("LCM encoding failed", error);
  return true;
}

namespace {

std::string SizeText(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// Compares what a compressed image's header declares with the intrinsics, before decoding.
bool CheckCompressed(const std::vector<uint8_t>& data, const char* name, ImageHeader::Format format,
                     const sensor::PinholeIntrinsics& k, ImageHeader* header, std::string* error) {
  if (data.empty()) return Fail(std::string(name) + " image is empty", error);
  if (!ReadImageHeader(data.data(), data.size(), header, error)) {
    return Fail(std::string(name) + " image: " + *error, error);
  }
  if (header->format != format) return Fail(std::string(name) + " image is not in its declared encoding", error);
  if (header->width != k.width || header->height != k.height) {
    return Fail(std::string(name) + " image declares " + SizeText(header->width, header->height) +
                    " but intrinsics say " + SizeText(k.width, k.height),
                error);
  }
  return true;
}

bool CheckColor(const RgbdImageData& images, const sensor::PinholeIntrinsics& kc, std::string* error) {
  if (images.color_encoding == "jpeg") {
    ImageHeader header;
    return CheckCompressed(images.color_data, "colour", ImageHeader::Format::kJpeg, kc, &header, error);
  }
  if (images.color_encoding == "rgb8") {
    if (images.color_data.size() != 3 * PixelCount(kc)) return Fail("rgb8 colour size does not match intrinsics", error);
    return true;
  }
  return Fail("unknown colour encoding '" + images.color_encoding + "'", error);
}

bool CheckDepth(const RgbdImageData& images, const sensor::PinholeIntrinsics& kd, std::string* error) {
  if (images.depth_encoding == "png16") {
    ImageHeader header;
    if (!CheckCompressed(images.depth_data, "depth", ImageHeader::Format::kPng, kd, &header, error)) return false;
    if (header.bit_depth != 16 || header.channels != 1) return Fail("depth image is not 16-bit single-channel", error);
    return true;
  }
  if (images.depth_encoding == "mono16") {
    if (images.depth_data.size() != 2 * PixelCount(kd)) return Fail("mono16 depth size does not match intrinsics", error);
    return true;
  }
  return Fail("unknown depth encoding '" + images.depth_encoding + "'", error);
}

// cv::imdecode reports some corrupt data by throwing (cv::Exception) rather than by an empty Mat.
cv::Mat ImDecode(const std::vector<uint8_t>& data, int flags) {
  try {
    return cv::imdecode(data, flags);
  } catch (const cv::Exception&) {
    return cv::Mat();
  }
}

}  // namespace

bool DecodeRgbdFrameHeader(const void* data, int size, sensor::RgbdFrame* frame,
                           RgbdImageData* images, std::string* error) {
  // The generated decoder trusts the counted fields (a bad count would make it resize to a
  // huge size or assign a negative-length string): check the layout first.
  lcm_wire::WireCursor layout(data, size);
  int64_t hash = 0;
  if (!layout.ReadInt64(&hash)) return Fail("truncated rgbd_frame_t (no fingerprint)", error);
  if (hash != fusemap_lcm::rgbd_frame_t::getHash()) return Fail("fingerprint is not rgbd_frame_t", error);
  // utime, frame, 2 x intrinsics (2 int32 + 4 double), 2 x transform (7 double), images.
  const bool layout_ok = layout.Skip(8) && layout.SkipString() && layout.Skip(2 * 40 + 2 * 56) &&
                         layout.SkipString() && layout.SkipBytes() && layout.SkipString() &&
                         layout.SkipBytes();
  if (!layout_ok) return Fail("truncated or corrupt rgbd_frame_t (bad length field)", error);
  if (!layout.AtEnd(nullptr)) return Fail("trailing bytes after rgbd_frame_t", error);
  fusemap_lcm::rgbd_frame_t msg;
  if (msg.decode(data, 0, size) != size) return Fail("rgbd_frame_t decode failed", error);

  sensor::RgbdFrame out;
  out.stamp_s = UtimeToStamp(msg.utime);
  out.frame = msg.frame;
  if (!FromLcm(msg.color_intrinsics, "colour intrinsics", &out.color_intrinsics, error) ||
      !FromLcm(msg.depth_intrinsics, "depth intrinsics", &out.depth_intrinsics, error) ||
      !FromLcm(msg.T_color_depth, "T_color_depth", &out.T_color_depth, error) ||
      !FromLcm(msg.T_base_color, "T_base_color", &out.T_base_color, error)) {
    return false;
  }
  RgbdImageData in;
  in.color_encoding = std::move(msg.color_encoding);
  in.color_data = std::move(msg.color_data);
  in.depth_encoding = std::move(msg.depth_encoding);
  in.depth_data = std::move(msg.depth_data);
  if (!CheckColor(in, out.color_intrinsics, error) || !CheckDepth(in, out.depth_intrinsics, error)) {
    return false;
  }
  *frame = std::move(out);
  *images = std::move(in);
  return true;
}

bool DecodeRgbdImages(const RgbdImageData& images, sensor::RgbdFrame* frame, std::string* error) {
  const sensor::PinholeIntrinsics& kc = frame->color_intrinsics;
  const sensor::PinholeIntrinsics& kd = frame->depth_intrinsics;
  // Cheap, and keeps the raw copies below in bounds whoever calls this.
  if (!CheckColor(images, kc, error) || !CheckDepth(images, kd, error)) return false;
  std::vector<uint8_t> color_rgb;
  if (images.color_encoding == "jpeg") {
    const cv::Mat bgr = ImDecode(images.color_data, cv::IMREAD_COLOR);
    if (bgr.empty()) return Fail("colour image (jpeg) cannot be decoded", error);
    if (bgr.cols != kc.width || bgr.rows != kc.height) {
      return Fail("colour image is " + SizeText(bgr.cols, bgr.rows) + " but intrinsics say " +
                      SizeText(kc.width, kc.height),
                  error);
    }
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    color_rgb.assign(rgb.data, rgb.data + 3 * PixelCount(kc));
  } else {
    color_rgb = images.color_data;
  }
  std::vector<uint16_t> depth_mm(PixelCount(kd));
  if (images.depth_encoding == "png16") {
    const cv::Mat depth = ImDecode(images.depth_data, cv::IMREAD_ANYDEPTH);
    if (depth.empty()) return Fail("depth image (png16) cannot be decoded", error);
    if (depth.type() != CV_16UC1) return Fail("depth image is not 16-bit single-channel", error);
    if (depth.cols != kd.width || depth.rows != kd.height) {
      return Fail("depth image is " + SizeText(depth.cols, depth.rows) + " but intrinsics say " +
                      SizeText(kd.width, kd.height),
                  error);
    }
    for (int r = 0; r < depth.rows; ++r) {
      std::memcpy(&depth_mm[static_cast<size_t>(r) * kd.width], depth.ptr<uint16_t>(r), 2 * kd.width);
    }
  } else {
    for (size_t i = 0; i < depth_mm.size(); ++i) {
      depth_mm[i] = static_cast<uint16_t>(images.depth_data[2 * i] | (images.depth_data[2 * i + 1] << 8));
    }
  }
  frame->color_rgb = std::move(color_rgb);
  frame->depth_mm = std::move(depth_mm);
  return true;
}

bool DecodeRgbdFrame(const void* data, int size, sensor::RgbdFrame* frame, std::string* error) {
  sensor::RgbdFrame out;
  RgbdImageData images;
  if (!DecodeRgbdFrameHeader(data, size, &out, &images, error) ||
      !DecodeRgbdImages(images, &out, error)) {
    return false;
  }
  *frame = std::move(out);
  return true;
}

}  // namespace io
}  // namespace fusemap
