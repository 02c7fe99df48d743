#include "fusemap/sensor/stamp_filter.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace fusemap {
namespace sensor {
namespace {

constexpr double kNever = -std::numeric_limits<double>::infinity();

std::string Format(const char* format, double a, double b, double c = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), format, a, b, c);
  return buffer;
}

}  // namespace

void StampFilterOptions::Check(common::OptionChecker* check) const {
  check->Require(std::isfinite(min_stamp_s), "min_stamp_s", "must be finite");
  check->Require(std::isfinite(max_stamp_s) && max_stamp_s > min_stamp_s, "max_stamp_s",
                 "must be finite and > min_stamp_s");
  check->Require(max_jump_s > 0.0 && std::isfinite(max_jump_s), "max_jump_s", "must be > 0");
  check->Require(time_reset_threshold_s >= 0.0 && std::isfinite(time_reset_threshold_s),
                 "time_reset_threshold_s", "must be >= 0");
  check->Require(max_time_reset_s >= time_reset_threshold_s && std::isfinite(max_time_reset_s),
                 "max_time_reset_s", "must be >= time_reset_threshold_s");
}

bool StampFilterOptions::IsValid(std::string* error) const {
  return common::IsValidOptions(*this, error);
}

StampFilter::StampFilter(const StampFilterOptions& options, int num_channels,
                         int reference_channel)
    : options_(options),
      reference_channel_(reference_channel),
      last_s_(num_channels, kNever),
      resume_s_(num_channels, kNever),
      suspects_(num_channels),
      newest_s_(kNever) {}

void StampFilter::SetResumePoint(int channel, double stamp_s) {
  resume_s_[channel] = stamp_s;
  last_s_[channel] = std::max(last_s_[channel], stamp_s);
  newest_s_ = std::max(newest_s_, stamp_s);
}

void StampFilter::Accept(int channel, double rebased_s) {
  resume_s_[channel] = kNever;  // the stream has passed the checkpoint
  last_s_[channel] = rebased_s;
  newest_s_ = std::max(newest_s_, rebased_s);
}

void StampFilter::Reset(int channel, double raw_s, std::string* reason) {
  const double jump_s = last_s_[channel] - (raw_s + offset_s_);
  offset_s_ += jump_s + kTimeResetGapS;
  ++time_resets_;
  *reason = Format("stamp %.6f is %.1f s before the previous one: new time base, incoming stamps "
                   "now shifted by %+.6f s",
                   raw_s, jump_s, offset_s_);
}

StampFilter::Decision StampFilter::Check(int channel, double raw_s) {
  Decision decision;
  if (!(std::isfinite(raw_s) && raw_s >= options_.min_stamp_s && raw_s <= options_.max_stamp_s)) {
    decision.verdict = Verdict::kReject;
    decision.kind = "absurd timestamp";
    decision.reason = Format("stamp %g is outside [%.0f, %.0f] s; dropped", raw_s,
                             options_.min_stamp_s, options_.max_stamp_s);
    return decision;
  }
  // Until a message of the channel is accepted past the checkpoint (an outlier held on the
  // way does not count), whatever the checkpoint already holds is skipped.
  if (resume_s_[channel] != kNever && raw_s <= resume_s_[channel]) {
    decision.verdict = Verdict::kSkip;
    decision.reason = Format("stamp %.6f is at or before the checkpoint's %.6f: already mapped",
                             raw_s, resume_s_[channel]);
    return decision;
  }
  Suspect& suspect = suspects_[channel];
  Held held = Held::kNone;
  double held_stamp_s = 0.0;
  std::string held_reason, reset_reason;
  if (suspect.active) {
    suspect.active = false;
    if (raw_s >= suspect.raw_s && raw_s - suspect.raw_s <= options_.max_jump_s) {
      if (suspect.backwards) Reset(channel, suspect.raw_s, &reset_reason);
      held = Held::kRelease;
      held_stamp_s = suspect.raw_s + offset_s_;
      Accept(channel, held_stamp_s);
    } else {
      held = Held::kDrop;
      held_reason = Format("stamp %.6f was a jump the next message (%.6f) did not follow: dropped "
                           "as an outlier",
                           suspect.raw_s, raw_s);
    }
  }
  decision = Judge(channel, raw_s);
  decision.held = held;
  decision.held_stamp_s = held_stamp_s;
  decision.held_reason = held_reason;
  if (!reset_reason.empty()) {
    decision.time_reset = true;
    decision.reason = reset_reason;
  }
  return decision;
}

StampFilter::Decision StampFilter::Judge(int channel, double raw_s) {
  Decision decision;
  double rebased_s = raw_s + offset_s_;
  const double last_s = last_s_[channel];
  if (channel == reference_channel_ && options_.time_reset_threshold_s > 0.0 &&
      rebased_s < last_s - options_.time_reset_threshold_s) {
    if (last_s - rebased_s <= options_.max_time_reset_s) {
      Reset(channel, raw_s, &decision.reason);
      decision.time_reset = true;
      rebased_s = raw_s + offset_s_;
    } else {
      suspects_[channel] = {true, raw_s, true};
      decision.verdict = Verdict::kHold;
      decision.kind = "timestamp jump";
      decision.reason = Format("stamp %.6f is %.0f s before the previous one, more than a log "
                               "loop: held until the next message confirms a new time base",
                               raw_s, last_s - rebased_s);
      return decision;
    }
  }
  if (rebased_s < last_s) {
    decision.verdict = Verdict::kReject;
    decision.kind = "timestamp going backwards";
    decision.reason =
        Format("stamp %.6f is before the previous %.6f; dropped", rebased_s, last_s);
    return decision;
  }
  if (newest_s_ != kNever && rebased_s > newest_s_ + options_.max_jump_s) {
    suspects_[channel] = {true, raw_s, false};
    decision.verdict = Verdict::kHold;
    decision.kind = "timestamp jump";
    decision.reason = Format("stamp %.6f is %.1f s ahead of the newest accepted stamp %.6f: held "
                             "until the next message confirms the new time base",
                             rebased_s, rebased_s - newest_s_, newest_s_);
    return decision;
  }
  Accept(channel, rebased_s);
  decision.stamp_s = rebased_s;
  return decision;
}

}  // namespace sensor
}  // namespace fusemap
