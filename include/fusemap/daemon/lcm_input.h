#ifndef FUSEMAP_DAEMON_LCM_INPUT_H_
#define FUSEMAP_DAEMON_LCM_INPUT_H_

#include <atomic>
#include <memory>
#include <string>

#include "fusemap/daemon/bounded_queue.h"
#include "fusemap/daemon/intake.h"

namespace lcm {
class LCM;
struct ReceiveBuffer;
}  // namespace lcm

namespace fusemap {
namespace daemon {

// True for LCM's log-file provider (file://...).
bool IsLogUrl(const std::string& lcm_url);

// Whether messages arrive at the pace they were sent: every live provider, and a log replayed
// at a speed other than 0 (LCM's default is 1). A file://...?speed=0 log is read as fast as
// the daemon takes it, so its SLAM thread is busy all the time.
bool ArrivesPaced(const std::string& lcm_url);

// The queues' overflow policy for a provider. A live network source must never block its
// handler (the socket would overflow and LCM would drop silently), so the oldest data goes. A
// log file has no real-time source: blocking the reader costs nothing and keeps a replay
// complete and deterministic, so file:// blocks instead.
OverflowPolicy PolicyForUrl(const std::string& lcm_url);

// Owns an LCM handle and feeds every message on the intake's channels into Intake::OnMessage.
// Run() is the LCM handler thread's body. The handle is also the publishers' (LCM is thread-safe).
class LcmInput {
 public:
  enum class End { kStopped, kEndOfLog, kError };

  LcmInput();
  ~LcmInput();
  LcmInput(const LcmInput&) = delete;
  LcmInput& operator=(const LcmInput&) = delete;

  // Opens `lcm_url`; false with a reason on failure.
  bool Open(const std::string& lcm_url, std::string* error);
  // Feeds the intake's channels into it; after Open, before Run.
  void Subscribe(Intake* intake);
  // Handles messages until `stop` is set (checked every `poll_ms`) or the provider reports an
  // end: with file:// that is the end of the log (kEndOfLog), otherwise an error (kError).
  End Run(const std::atomic<bool>& stop, int poll_ms = 100);
  // For publishing on the same bus (null for file://, where there is nowhere to publish).
  lcm::LCM* publish_handle();

 private:
  // LCM's callback for every subscribed channel (`self` is the context given to LCM).
  static void OnRaw(const lcm::ReceiveBuffer* buffer, const std::string& channel, LcmInput* self);

  Intake* intake_ = nullptr;
  std::unique_ptr<lcm::LCM> lcm_;
  bool is_log_ = false;
};

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_LCM_INPUT_H_
