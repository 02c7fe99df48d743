#include "fusemap/daemon/this_thread.h"

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
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
