#ifndef FUSEMAP_COMMON_PROCESS_MEMORY_H_
#define FUSEMAP_COMMON_PROCESS_MEMORY_H_

#include <cstdint>

namespace fusemap {
namespace common {

// Resident set size of this process from /proc/self/statm, or 0 where that is unavailable.
int64_t ResidentMemoryBytes();

// Returns free heap pages to the system (glibc's malloc_trim; a no-op elsewhere). Large grids
// freed in the middle of the heap otherwise stay resident until the heap above them empties.
void ReleaseFreeMemory();

}  // namespace common
}  // namespace fusemap

#endif  // FUSEMAP_COMMON_PROCESS_MEMORY_H_
