#include "fusemap/daemon/this_thread.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <string>
#include <thread>

namespace fusemap {
namespace daemon {
namespace {

int ThisThreadPolicy() {
  int policy = -1;
  sched_param param{};
  pthread_getschedparam(pthread_self(), &policy, &param);
  return policy;
}

TEST(ThisThreadTest, NameIsCutToWhatLinuxKeeps) {
  char name[32] = {};
  std::thread worker([&] {
    SetThisThreadName("fusemap-publisher-thread");
    pthread_getname_np(pthread_self(), name, sizeof(name));
  });
  worker.join();
  EXPECT_STREQ(name, "fusemap-publish");
}

// The suite may itself run niced (`nice bash tools/run_sanitizers.sh`, a CI runner): the
// calling thread keeps the nice value it started with, whatever that is.
TEST(ThisThreadTest, LowerPriorityChangesOnlyTheCallingThread) {
  const int nice_before = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
  // 7, or one lower in priority than the suite if it already runs at 7 or more.
  const int nice = std::min(19, std::max(7, nice_before + 1));
  if (nice == nice_before) GTEST_SKIP() << "the suite runs at nice 19: no lower priority to set";
  int worker_nice = 0;
  std::thread worker([&] {
    LowerThisThreadPriority(nice);
    worker_nice = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
  });
  worker.join();
  EXPECT_EQ(worker_nice, nice);
  EXPECT_EQ(getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid))), nice_before);
}

TEST(ThisThreadTest, RealtimeOutsideTheRangeIsRefusedWithTheReason) {
  std::string error;
  EXPECT_FALSE(SetThisThreadRealtime(0, &error));
  EXPECT_NE(error.find("outside [1, 99]"), std::string::npos) << error;
  EXPECT_FALSE(SetThisThreadRealtime(100, &error));
  EXPECT_EQ(ThisThreadPolicy(), SCHED_OTHER);
}

// Granted (root, CAP_SYS_NICE, RLIMIT_RTPRIO) the thread is under SCHED_FIFO; refused it keeps
// its policy and says why. Either way only the calling thread changes.
TEST(ThisThreadTest, RealtimeIsGrantedOrRefusedWithTheReason) {
  bool granted = false;
  int policy = -1;
  std::string error;
  std::thread worker([&] {
    granted = SetThisThreadRealtime(1, &error);
    policy = ThisThreadPolicy();
  });
  worker.join();
  if (granted) {
    EXPECT_EQ(policy, SCHED_FIFO);
  } else {
    EXPECT_EQ(policy, SCHED_OTHER);
    EXPECT_NE(error.find("refused"), std::string::npos) << error;
  }
  EXPECT_EQ(ThisThreadPolicy(), SCHED_OTHER);
}

}  // namespace
}  // namespace daemon
}  // namespace fusemap
