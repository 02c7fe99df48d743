#include "fusemap/io/lcm_log.h"

#include <lcm/lcm-cpp.hpp>

#include <filesystem>

namespace fusemap {
namespace io {

LcmLogWriter::LcmLogWriter() = default;
LcmLogWriter::~LcmLogWriter() = default;

bool LcmLogWriter::Open(const std::string& path, std::string* error) {
  file_ = std::make_unique<lcm::LogFile>(path, "w");
  if (!file_->good()) {
    file_.reset();
    if (error != nullptr) *error = path + ": cannot open LCM log for writing";
    return false;
  }
  num_written_ = 0;
  return true;
}

bool LcmLogWriter::Write(const std::string& channel, int64_t utime, const void* data, int size) {
  if (file_ == nullptr || size < 0) return false;
  lcm::LogEvent event;
  event.eventnum = num_written_;
  event.timestamp = utime;
  event.channel = channel;
  event.datalen = size;
  event.data = const_cast<void*>(data);  // LogFile::writeEvent only reads the payload.
  if (file_->writeEvent(&event) != 0) return false;
  ++num_written_;
  return true;
}

void LcmLogWriter::Close() { file_.reset(); }

LcmLogReader::LcmLogReader() = default;
LcmLogReader::~LcmLogReader() = default;

bool LcmLogReader::Open(const std::string& path, std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    if (error != nullptr) *error = path + ": is a directory, not an LCM log";
    return false;
  }
  file_ = std::make_unique<lcm::LogFile>(path, "r");
  if (!file_->good()) {
    file_.reset();
    if (error != nullptr) *error = path + ": cannot open LCM log for reading";
    return false;
  }
  return true;
}

bool LcmLogReader::Next(LogEvent* event) {
  if (file_ == nullptr) return false;
  const lcm::LogEvent* raw = file_->readNextEvent();
  if (raw == nullptr) return false;
  event->channel = raw->channel;
  event->utime = raw->timestamp;
  const uint8_t* bytes = static_cast<const uint8_t*>(raw->data);
  event->data.assign(bytes, bytes + raw->datalen);
  return true;
}

}  // namespace io
}  // namespace fusemap
