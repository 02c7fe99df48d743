#ifndef FUSEMAP_IO_LCM_LOG_H_
#define FUSEMAP_IO_LCM_LOG_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lcm {
class LogFile;
}  // namespace lcm

namespace fusemap {
namespace io {

// One message of an LCM log: channel, event timestamp (microseconds) and encoded bytes.
struct LogEvent {
  std::string channel;
  int64_t utime = 0;
  std::vector<uint8_t> data;
};

// Writes an LCM log file directly (lcm::LogFile in "w" mode; no network involved). The file
// is complete once Close() is called or the writer is destroyed.
class LcmLogWriter {
 public:
  LcmLogWriter();
  ~LcmLogWriter();
  LcmLogWriter(const LcmLogWriter&) = delete;
  LcmLogWriter& operator=(const LcmLogWriter&) = delete;

  bool Open(const std::string& path, std::string* error);
  // Raw, already encoded message bytes.
  bool Write(const std::string& channel, int64_t utime, const void* data, int size);
  // Any lcm-gen generated message type.
  template <class Msg>
  bool Write(const std::string& channel, int64_t utime, const Msg& msg) {
    std::vector<uint8_t> bytes(msg.getEncodedSize());
    if (msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())) < 0) return false;
    return Write(channel, utime, bytes.data(), static_cast<int>(bytes.size()));
  }
  void Close();
  int64_t num_written() const { return num_written_; }

 private:
  std::unique_ptr<lcm::LogFile> file_;
  int64_t num_written_ = 0;
};

// Reads an LCM log file event by event, in file order.
class LcmLogReader {
 public:
  LcmLogReader();
  ~LcmLogReader();
  LcmLogReader(const LcmLogReader&) = delete;
  LcmLogReader& operator=(const LcmLogReader&) = delete;

  bool Open(const std::string& path, std::string* error);
  // False at the end of the file (or at a corrupt event, which ends reading too).
  bool Next(LogEvent* event);

 private:
  std::unique_ptr<lcm::LogFile> file_;
};

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_LCM_LOG_H_
