#include "fusemap/daemon/this_thread.h"

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>

namespace fusemap {
namespace daemon {
namespace {

id_t ThisThreadId() { return static_cast<id_t>(syscall(SYS_gettid)); }

}  // namespace

void SetThisThreadName(const std::string& name) {
  pthread_setname_np(pthread_self(), name.substr(0, 15).c_str());
}

void LowerThisThreadPriority(int nice) { setpriority(PRIO_PROCESS, ThisThreadId(), nice); }

void RequestShortSlice() {
  // struct sched_attr as the kernel defines it; glibc 2.36 has no wrapper.
  struct {
    uint32_t size;
    uint32_t sched_policy;
    uint64_t sched_flags;
    int32_t sched_nice;
    uint32_t sched_priority;
    uint64_t sched_runtime;  // for SCHED_OTHER: the slice, ns
    uint64_t sched_deadline;
    uint64_t sched_period;
  } attr{};
  attr.size = sizeof(attr);
  attr.sched_policy = SCHED_OTHER;
  attr.sched_nice = getpriority(PRIO_PROCESS, ThisThreadId());
  attr.sched_runtime = 100'000;  // the kernel's minimum
  syscall(SYS_sched_setattr, 0, &attr, 0);
}

bool SetThisThreadRealtime(int priority, std::string* error) {
  const int min_priority = sched_get_priority_min(SCHED_FIFO);
  const int max_priority = sched_get_priority_max(SCHED_FIFO);
  if (priority < min_priority || priority > max_priority) {
    *error = "SCHED_FIFO priority " + std::to_string(priority) + " outside [" +
             std::to_string(min_priority) + ", " + std::to_string(max_priority) + "]";
    return false;
  }
  sched_param param{};
  param.sched_priority = priority;
  const int result = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
  if (result == 0) return true;
  *error = "SCHED_FIFO priority " + std::to_string(priority) +
           " refused: " + std::strerror(result) +
           (result == EPERM ? " (needs root, CAP_SYS_NICE or RLIMIT_RTPRIO >= the priority)" : "");
  return false;
}

}  // namespace daemon
}  // namespace fusemap
