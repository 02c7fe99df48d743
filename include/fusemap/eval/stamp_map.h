#ifndef FUSEMAP_EVAL_STAMP_MAP_H_
#define FUSEMAP_EVAL_STAMP_MAP_H_

#include <cstddef>
#include <vector>

#include "fusemap/eval/relation_error.h"

namespace fusemap {
namespace eval {

// One record of a converted log: the stamp it was given on output (spread over its rounding
// interval, or moved forward where the log's stamps went backwards) and the stamp the log
// printed, with the width of that print's rounding interval.
struct StampMapEntry {
  double output_s = 0.0;
  double log_s = 0.0;
  double log_resolution_s = 0.0;
};

// Translates a time on the original log's clock (ground truth taken from the raw log, e.g.
// Kümmerle relations) onto the converted log's time base. Where the importer repaired stamps,
// looking such a time up directly lands on the wrong records: in the Intel log some stretches
// of stamps run backwards, so one printed stamp names records up to a second apart in file
// order, and 272 of the 2,984 relations had a stamp more than 50 ms from any output stamp.
// The time is attributed to the records whose printed stamp it rounds to, at its place within
// their rounding interval.
class StampMap {
 public:
  enum class Match {
    kExact,      // one run of consecutive records prints the stamp
    kAmbiguous,  // several runs do; the one whose output stamps are nearest the time is used
    kUnmatched,  // no record prints it; the time is returned unchanged
  };

  // Entries in file order; output stamps must be non-decreasing (as the importer writes them).
  explicit StampMap(std::vector<StampMapEntry> entries);

  double ToOutputTime(double log_time_s, Match* match = nullptr) const;
  size_t size() const { return entries_.size(); }

 private:
  double PlaceInRun(size_t first, size_t last, double log_time_s) const;

  std::vector<StampMapEntry> entries_;
  std::vector<size_t> by_log_stamp_;  // entry indices sorted by log_s
  double max_resolution_s_ = 0.0;
};

struct StampMapCounts {
  int exact = 0;
  int ambiguous = 0;
  int unmatched = 0;
};

// Maps both stamps of every relation onto the output time base.
StampMapCounts MapRelationTimes(const StampMap& map, std::vector<Relation>* relations);

}  // namespace eval
}  // namespace fusemap

#endif  // FUSEMAP_EVAL_STAMP_MAP_H_
