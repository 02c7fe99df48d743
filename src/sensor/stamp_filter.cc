#include "fusemap/sensor/stamp_filter.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

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
  // After the newest stamp of every channel, so that none of the new loop's messages is
  // behind its channel's last one of the old loop.
  offset_s_ += newest_s_ - (raw_s + offset_s_) + kTimeResetGapS;
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
  double held_stamp_s = 0.0;
  std::string held_reason, reset_reason;
  const Held held = ResolveSuspect(channel, raw_s, &held_stamp_s, &held_reason, &reset_reason);
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

StampFilter::Held StampFilter::ResolveSuspect(int channel, double raw_s, double* held_stamp_s,
                                              std::string* held_reason,
                                              std::string* reset_reason) {
  Suspect& suspect = suspects_[channel];
  if (!suspect.active) return Held::kNone;
  suspect.active = false;
  const bool follows = raw_s >= suspect.raw_s && raw_s - suspect.raw_s <= options_.max_jump_s;
  bool release = follows;
  if (suspect.backwards && channel != reference_channel_) {
    if (time_resets_ > suspect.time_resets) {
      // The laser moved to the new time base meanwhile: the held message belongs to it.
      const double rebased_s = suspect.raw_s + offset_s_;
      release = rebased_s >= last_s_[channel] && rebased_s <= newest_s_ + options_.max_jump_s;
    } else {
      // Confirmed only by a message that is on the new clock too, not back on the old one.
      release = follows && raw_s + offset_s_ < last_s_[channel] - options_.time_reset_threshold_s;
      if (release) Reset(channel, suspect.raw_s, reset_reason);
    }
  } else if (release && suspect.backwards) {
    Reset(channel, suspect.raw_s, reset_reason);
  }
  if (!release) {
    *held_reason = Format("stamp %.6f was a jump the next message (%.6f) did not follow: dropped "
                          "as an outlier",
                          suspect.raw_s, raw_s);
    return Held::kDrop;
  }
  *held_stamp_s = suspect.raw_s + offset_s_;
  Accept(channel, *held_stamp_s);
  return Held::kRelease;
}

StampFilter::Decision StampFilter::Hold(int channel, double raw_s, bool backwards,
                                        std::string reason) {
  suspects_[channel] = {true, raw_s, backwards, time_resets_};
  Decision decision;
  decision.verdict = Verdict::kHold;
  decision.kind = "timestamp jump";
  decision.reason = std::move(reason);
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
      return Hold(channel, raw_s, true,
                  Format("stamp %.6f is %.0f s before the previous one, more than a log loop: "
                         "held until the next message confirms a new time base",
                         raw_s, last_s - rebased_s));
    }
  }
  if (channel != reference_channel_ && options_.time_reset_threshold_s > 0.0 &&
      rebased_s < last_s - options_.time_reset_threshold_s &&
      last_s - rebased_s <= options_.max_time_reset_s) {
    return Hold(channel, raw_s, true,
                Format("stamp %.6f is %.1f s before the previous one: held until the laser or the "
                       "next message confirms a new time base",
                       raw_s, last_s - rebased_s));
  }
  if (rebased_s < last_s) {
    decision.verdict = Verdict::kReject;
    decision.kind = "timestamp going backwards";
    decision.reason =
        Format("stamp %.6f is before the previous %.6f; dropped", rebased_s, last_s);
    return decision;
  }
  if (newest_s_ != kNever && rebased_s > newest_s_ + options_.max_jump_s) {
    return Hold(channel, raw_s, false,
                Format("stamp %.6f is %.1f s ahead of the newest accepted stamp %.6f: held until "
                       "the next message confirms the new time base",
                       rebased_s, rebased_s - newest_s_, newest_s_));
  }
  Accept(channel, rebased_s);
  decision.stamp_s = rebased_s;
  return decision;
}

}  // namespace sensor
}  // namespace fusemap
