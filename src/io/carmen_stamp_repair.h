#ifndef FUSEMAP_IO_CARMEN_STAMP_REPAIR_H_
#define FUSEMAP_IO_CARMEN_STAMP_REPAIR_H_

#include <string>
#include <vector>

namespace fusemap {
namespace io {

// Width of the rounding interval of a stamp as printed in a log, in seconds; 0 for a zero or
// unparsable stamp. GMapping prints with 6 significant digits (C++ stream default), so above
// 1000 s "1401.34" stands for [1401.335, 1401.345); a text with more digits than that
// (CARMEN's "%f") resolves its last decimal. The narrower of the two readings is returned, so
// a stamp is never spread further than its text allows.
double PrintedStampResolution(const std::string& text);

// Stamps for consecutive records that all print `printed_s`: the distinct instants among them
// are spread evenly over the rounding interval [printed_s - r/2, printed_s + r/2), instant i
// of k at printed_s - r/2 + (i + 0.5) r / k, in file order. starts_instant[i] is false for a
// record that happened together with the one before it (a scan and the ODOM line printed just
// before it); starts_instant[0] is treated as true. One stamp per record is returned.
std::vector<double> SpreadOverRounding(double printed_s, double resolution_s,
                                       const std::vector<bool>& starts_instant);

}  // namespace io
}  // namespace fusemap

#endif  // FUSEMAP_IO_CARMEN_STAMP_REPAIR_H_
