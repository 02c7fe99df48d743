#include "fusemap/eval/stamp_map.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fusemap {
namespace eval {
namespace {

// Relation stamps carry microseconds; a time on an interval's edge belongs to both prints.
constexpr double kEdgeToleranceS = 1e-7;

bool Prints(const StampMapEntry& e, double log_time_s) {
  return std::abs(log_time_s - e.log_s) <= 0.5 * e.log_resolution_s + kEdgeToleranceS;
}

}  // namespace

StampMap::StampMap(std::vector<StampMapEntry> entries) : entries_(std::move(entries)) {
  by_log_stamp_.resize(entries_.size());
  for (size_t i = 0; i < entries_.size(); ++i) {
    by_log_stamp_[i] = i;
    max_resolution_s_ = std::max(max_resolution_s_, entries_[i].log_resolution_s);
  }
  std::stable_sort(by_log_stamp_.begin(), by_log_stamp_.end(), [this](size_t a, size_t b) {
    return entries_[a].log_s < entries_[b].log_s;
  });
}

double StampMap::PlaceInRun(size_t first, size_t last, double log_time_s) const {
  // The importer spread a run's distinct instants evenly over the rounding interval; the
  // time's place in the interval picks its place among them. Where late stamps were moved,
  // neighbouring instants can lie far apart on output: then the nearer one is taken as is.
  std::vector<double> instants_s;
  double low_s = INFINITY, high_s = -INFINITY;
  for (size_t i = first; i <= last; ++i) {
    const StampMapEntry& e = entries_[i];
    if (instants_s.empty() || e.output_s != instants_s.back()) instants_s.push_back(e.output_s);
    low_s = std::min(low_s, e.log_s - 0.5 * e.log_resolution_s);
    high_s = std::max(high_s, e.log_s + 0.5 * e.log_resolution_s);
  }
  const double k = static_cast<double>(instants_s.size());
  const double fraction =
      high_s > low_s ? std::clamp((log_time_s - low_s) / (high_s - low_s), 0.0, 1.0) : 0.0;
  const double x = std::clamp(fraction * k - 0.5, 0.0, k - 1.0);
  const size_t lower = static_cast<size_t>(x);
  if (lower + 1 >= instants_s.size()) return instants_s.back();
  const double a_s = instants_s[lower], b_s = instants_s[lower + 1];
  const double w = x - static_cast<double>(lower);
  const auto in_interval = [&](double t_s) { return t_s >= low_s && t_s <= high_s; };
  if (!in_interval(a_s) || !in_interval(b_s)) return w < 0.5 ? a_s : b_s;
  return a_s + w * (b_s - a_s);
}

double StampMap::ToOutputTime(double log_time_s, Match* match) const {
  const double reach_s = 0.5 * max_resolution_s_ + kEdgeToleranceS;
  const auto begin = std::lower_bound(
      by_log_stamp_.begin(), by_log_stamp_.end(), log_time_s - reach_s,
      [this](size_t i, double t) { return entries_[i].log_s < t; });
  std::vector<size_t> candidates;
  for (auto it = begin; it != by_log_stamp_.end() && entries_[*it].log_s <= log_time_s + reach_s;
       ++it) {
    if (Prints(entries_[*it], log_time_s)) candidates.push_back(*it);
  }
  if (candidates.empty()) {
    if (match != nullptr) *match = Match::kUnmatched;
    return log_time_s;
  }
  std::sort(candidates.begin(), candidates.end());
  // Runs of consecutive records; of several, the one whose output stamps lie nearest the time
  // (what a direct look-up would have chosen).
  double best_distance_s = INFINITY, best_s = log_time_s;
  int runs = 0;
  for (size_t start = 0; start < candidates.size();) {
    size_t end = start;
    while (end + 1 < candidates.size() && candidates[end + 1] == candidates[end] + 1) ++end;
    ++runs;
    const double first_s = entries_[candidates[start]].output_s;
    const double last_s = entries_[candidates[end]].output_s;
    const double distance_s = std::max({0.0, first_s - log_time_s, log_time_s - last_s});
    if (distance_s < best_distance_s) {
      best_distance_s = distance_s;
      best_s = PlaceInRun(candidates[start], candidates[end], log_time_s);
    }
    start = end + 1;
  }
  if (match != nullptr) *match = runs == 1 ? Match::kExact : Match::kAmbiguous;
  return best_s;
}

StampMapCounts MapRelationTimes(const StampMap& map, std::vector<Relation>* relations) {
  StampMapCounts counts;
  auto map_one = [&](double* t_s) {
    StampMap::Match match;
    *t_s = map.ToOutputTime(*t_s, &match);
    switch (match) {
      case StampMap::Match::kExact: ++counts.exact; break;
      case StampMap::Match::kAmbiguous: ++counts.ambiguous; break;
      case StampMap::Match::kUnmatched: ++counts.unmatched; break;
    }
  };
  for (Relation& r : *relations) {
    map_one(&r.t1_s);
    map_one(&r.t2_s);
  }
  return counts;
}

}  // namespace eval
}  // namespace fusemap
