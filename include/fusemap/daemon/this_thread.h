#ifndef FUSEMAP_DAEMON_THIS_THREAD_H_
#define FUSEMAP_DAEMON_THIS_THREAD_H_

#include <string>

namespace fusemap {
namespace daemon {

// Name and scheduling of the calling thread (Linux schedules threads, not processes). The
// daemon's threads are of two kinds: those between a scan's receipt and its pose (LCM handler,
// SLAM thread) and those that may lag (global SLAM's workers, the report, RGB-D and visual
// threads).

// Names the calling thread for top -H, ps -L, perf and gdb ("fusemap-slam"); Linux keeps the
// first 15 characters.
void SetThisThreadName(const std::string& name);

// Raises the calling thread's nice value to `nice` (a lower priority). Needs no privilege;
// failing to is harmless, so it reports nothing.
void LowerThisThreadPriority(int nice);

// Puts the calling thread under SCHED_FIFO at `priority` (1-99): it then preempts every
// normally scheduled thread at wake-up. Needs root, CAP_SYS_NICE or an RLIMIT_RTPRIO of at
// least `priority`; on refusal returns false with the reason and leaves the thread as it was.
bool SetThisThreadRealtime(int priority, std::string* error);

}  // namespace daemon
}  // namespace fusemap

#endif  // FUSEMAP_DAEMON_THIS_THREAD_H_
