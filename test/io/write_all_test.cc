#include "write_all.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fusemap/io/tum_trajectory.h"

namespace fusemap {
namespace io {
namespace {

namespace fs = std::filesystem;

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class WriteAllTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir_template[] = "/tmp/fusemap_write_all_XXXXXX";
    ASSERT_NE(mkdtemp(dir_template), nullptr);
    dir_ = dir_template;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string dir_;
};

TEST_F(WriteAllTest, ReplacesTheFileAndLeavesNoTemporary) {
  const std::string path = dir_ + "/a.txt";
  std::string error;
  ASSERT_TRUE(WriteFileAtomically(path, "old\n", &error)) << error;
  ASSERT_TRUE(WriteFileAtomically(path, "new\n", &error)) << error;
  EXPECT_EQ(ReadText(path), "new\n");
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

// Issue 18 item 12: on a full disk trajectory.tum failed with "write failed" and no reason,
// and a truncated file was left in place. A file size limit (RLIMIT_FSIZE, in a child so the
// test process keeps its own) makes every write past 4 KiB fail with EFBIG as a full disk
// would with ENOSPC: the writer must say why, keep the old file whole and remove its temporary.
TEST_F(WriteAllTest, FullDiskKeepsTheOldFileAndSaysWhy) {
  const std::string path = dir_ + "/trajectory.tum";
  std::string error;
  ASSERT_TRUE(WriteFileAtomically(path, "previous run\n", &error)) << error;
  eval::Trajectory trajectory;
  for (int i = 0; i < 1000; ++i) trajectory.push_back({1.0 + i, common::Rigid3d()});
  int pipe_fd[2];
  ASSERT_EQ(pipe(pipe_fd), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(pipe_fd[0]);
    std::signal(SIGXFSZ, SIG_IGN);
    const struct rlimit limit = {4096, 4096};
    setrlimit(RLIMIT_FSIZE, &limit);
    std::string child_error;
    const bool ok = WriteTumTrajectoryFile(path, trajectory, &child_error);
    (void)!::write(pipe_fd[1], child_error.data(), child_error.size());
    _exit(ok ? 0 : 1);
  }
  ::close(pipe_fd[1]);
  std::string child_error;
  char buffer[256];
  ssize_t n;
  while ((n = ::read(pipe_fd[0], buffer, sizeof(buffer))) > 0) child_error.append(buffer, n);
  ::close(pipe_fd[0]);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1) << "the write past the size limit succeeded";
  EXPECT_EQ(child_error, path + ": write failed: " + std::strerror(EFBIG));
  EXPECT_EQ(ReadText(path), "previous run\n");
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST_F(WriteAllTest, PathWriterFailureRemovesTheTemporary) {
  const std::string path = dir_ + "/cloud.ply";
  std::string error;
  EXPECT_FALSE(WriteFileAtomically(
      path,
      [](const std::string& tmp, std::string* write_error) {
        std::ofstream(tmp) << "partial";
        *write_error = "library failed";
        return false;
      },
      &error));
  EXPECT_EQ(error, "library failed");
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

}  // namespace
}  // namespace io
}  // namespace fusemap
