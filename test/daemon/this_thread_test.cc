#include "fusemap/daemon/this_thread.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

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

TEST(ThisThreadTest, LowerPriorityChangesOnlyTheCallingThread) {
  int worker_nice = 0;
  std::thread worker([&] {
    LowerThisThreadPriority(7);
    worker_nice = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
  });
  worker.join();
  EXPECT_EQ(worker_nice, 7);
  EXPECT_EQ(getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid))), 0);
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
