#include "fusemap/daemon/lcm_input.h"

#include <cstdlib>
#include <lcm/lcm-cpp.hpp>

namespace fusemap {
namespace daemon {

bool IsLogUrl(const std::string& lcm_url) { return lcm_url.rfind("file://", 0) == 0; }

bool ArrivesPaced(const std::string& lcm_url) {
  if (!IsLogUrl(lcm_url)) return true;
  const size_t query = lcm_url.find('?');
  if (query == std::string::npos) return true;
  // Parameters are name=value pairs separated by '&'.
  size_t begin = query + 1;
  while (begin <= lcm_url.size()) {
    size_t end = lcm_url.find('&', begin);
    if (end == std::string::npos) end = lcm_url.size();
    const std::string parameter = lcm_url.substr(begin, end - begin);
    if (parameter.rfind("speed=", 0) == 0) {
      return std::strtod(parameter.c_str() + 6, nullptr) != 0.0;
    }
    begin = end + 1;
  }
  return true;
}

OverflowPolicy PolicyForUrl(const std::string& lcm_url) {
  return IsLogUrl(lcm_url) ? OverflowPolicy::kBlock : OverflowPolicy::kDropOldest;
}

LcmInput::LcmInput() = default;

LcmInput::~LcmInput() = default;

bool LcmInput::Open(const std::string& lcm_url, std::string* error) {
  is_log_ = IsLogUrl(lcm_url);
  lcm_ = std::make_unique<lcm::LCM>(lcm_url);
  if (!lcm_->good()) {
    *error = "cannot open LCM URL '" + lcm_url + "'" +
             (is_log_ ? " (is the log file readable?)" : "");
    lcm_.reset();
    return false;
  }
  return true;
}

void LcmInput::Subscribe(Intake* intake) {
  intake_ = intake;
  for (const std::string& name : intake_->channel_names()) {
    if (name.empty()) continue;
    // LCM treats channel names as regular expressions; anchor-free names match themselves.
    // A plain function with a context pointer, not subscribe(name, &LcmInput::OnRaw, this):
    // GCC's -fsanitize=vptr (part of -fsanitize=undefined, GCC 10-12 at least) instruments the
    // member-function-pointer call in LCM's trampoline, `(subs->handler->*subs->handlerMethod)`
    // (lcm-cpp-impl.hpp:108), with a wrong address, so every UBSan fusemapd aborted ("invalid
    // vptr") or segfaulted at its first message (GCC only; the same bug is reported in
    // dotnet/runtime#73927). LCM calls this plain function without a member pointer.
    lcm_->subscribeFunction(name, &LcmInput::OnRaw, this);
  }
}

void LcmInput::OnRaw(const lcm::ReceiveBuffer* buffer, const std::string& channel,
                     LcmInput* self) {
  self->intake_->OnMessage(channel, buffer->data, static_cast<int>(buffer->data_size));
}

LcmInput::End LcmInput::Run(const std::atomic<bool>& stop, int poll_ms) {
  while (!stop) {
    // 0 = timeout, > 0 = handled a message, < 0 = the provider is done (end of a log) or broken.
    if (lcm_->handleTimeout(poll_ms) < 0) return is_log_ ? End::kEndOfLog : End::kError;
  }
  return End::kStopped;
}

lcm::LCM* LcmInput::publish_handle() { return is_log_ ? nullptr : lcm_.get(); }

}  // namespace daemon
}  // namespace fusemap
