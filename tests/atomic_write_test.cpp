#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "edgefront/atomic_write.h"
#include "edgefront/error.h"

namespace fs = std::filesystem;
using edgefront::IoError;
using edgefront::write_file_atomically;

namespace {

/// A fresh, empty directory for one test, removed afterwards.
class AtomicWriteTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("edgefront_atomic_" + std::to_string(::getpid()) + "_" + std::string(info->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  size_t entries() const {
    size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  fs::path dir_;
};

}  // namespace

TEST_F(AtomicWriteTest, WritesANewFile) {
  const fs::path target = dir_ / "out.txt";
  write_file_atomically(
      target, [](std::ostream& os) { os << "hello\n"; }, false);
  EXPECT_EQ(slurp(target), "hello\n");
  EXPECT_EQ(entries(), 1u) << "a temporary file was left behind";
}

TEST_F(AtomicWriteTest, ReplacesAnExistingFileAndKeepsItsPermissions) {
  const fs::path target = dir_ / "out.bin";
  { std::ofstream(target) << "old content"; }
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  const std::string binary("a\0b\n", 4);
  write_file_atomically(
      target, [&](std::ostream& os) { os.write(binary.data(), 4); }, true);
  EXPECT_EQ(slurp(target), binary);
  EXPECT_EQ(fs::status(target).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicWriteTest, ThrowingBodyLeavesTheOldFileAndNoTemporary) {
  const fs::path target = dir_ / "keep.txt";
  { std::ofstream(target) << "precious"; }
  try {
    write_file_atomically(
        target,
        [](std::ostream& os) {
          os << "half of the new content";
          throw std::runtime_error("generator failed");
        },
        false);
    FAIL() << "no exception";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("keep.txt"), std::string::npos) << what;
    EXPECT_NE(what.find("generator failed"), std::string::npos) << what;
    // The original exception travels along as a nested exception.
    try {
      std::rethrow_if_nested(e);
      FAIL() << "no nested exception";
    } catch (const std::runtime_error& inner) {
      EXPECT_STREQ(inner.what(), "generator failed");
    }
  }
  EXPECT_EQ(slurp(target), "precious");
  EXPECT_EQ(entries(), 1u) << "a temporary file was left behind";
}

TEST_F(AtomicWriteTest, StreamErrorIsReported) {
  const fs::path target = dir_ / "bad_stream.txt";
  { std::ofstream(target) << "old"; }
  EXPECT_THROW(write_file_atomically(
                   target, [](std::ostream& os) { os.setstate(std::ios::badbit); }, false),
               IoError);
  EXPECT_EQ(slurp(target), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicWriteTest, MissingDirectoryGivesIoErrorNamingThePath) {
  const fs::path target = dir_ / "no_such_dir" / "out.txt";
  try {
    write_file_atomically(
        target, [](std::ostream& os) { os << "x"; }, false);
    FAIL() << "no exception";
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(target.string()), std::string::npos) << what;
    EXPECT_NE(what.find("does not exist"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(target));
}

TEST_F(AtomicWriteTest, UnwritableDirectoryGivesIoError) {
  // Permission bits do not stop root, so also use a "directory" that is a regular file: no
  // process can create a file inside it.
  const fs::path not_a_dir = dir_ / "plain_file";
  { std::ofstream(not_a_dir) << "x"; }
  EXPECT_THROW(write_file_atomically(
                   not_a_dir / "out.txt", [](std::ostream& os) { os << "x"; }, false),
               IoError);

  const fs::path locked = dir_ / "locked";
  fs::create_directories(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  const bool is_root = ::geteuid() == 0;
  if (!is_root) {
    EXPECT_THROW(write_file_atomically(
                     locked / "out.txt", [](std::ostream& os) { os << "x"; }, false),
                 IoError);
    EXPECT_FALSE(fs::exists(locked / "out.txt"));
  }
  fs::permissions(locked, fs::perms::owner_all);
}

TEST_F(AtomicWriteTest, TargetThatIsADirectoryIsRefused) {
  fs::create_directories(dir_ / "sub");
  EXPECT_THROW(write_file_atomically(
                   dir_ / "sub", [](std::ostream& os) { os << "x"; }, false),
               IoError);
  EXPECT_TRUE(fs::is_directory(dir_ / "sub"));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicWriteTest, FifoAndDeviceTargetsAreNotReplaced) {
  // Renaming over them would turn a FIFO, or /dev/null through a link, into a regular file.
  ASSERT_EQ(::mkfifo((dir_ / "pipe.txt").c_str(), 0600), 0);
  fs::create_symlink("/dev/null", dir_ / "null.txt");
  for (const char* name : {"pipe.txt", "null.txt"}) {
    try {
      write_file_atomically(dir_ / name, [](std::ostream& os) { os << "x"; }, false);
      ADD_FAILURE() << name << " was replaced";
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_fifo(dir_ / "pipe.txt"));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "null.txt"));
  EXPECT_EQ(entries(), 2u);
}

TEST_F(AtomicWriteTest, StaleTemporariesOfDeadProcessesAreRemovedByTheNextWrite) {
  // A process id that no longer runs: a child that has exited and been reaped.
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_NE(::kill(child, 0), 0);
  const std::string dead = std::to_string(child);
  const std::string alive = std::to_string(::getppid());  // the test runner's parent runs
  const std::vector<std::string> stale = {".out.txt.tmp-" + dead + "-0", ".out.txt.tmp-" + dead + "-17"};
  const std::vector<std::string> kept = {
      ".out.txt.tmp-" + alive + "-0",   // a live process may still be writing
      ".other.txt.tmp-" + dead + "-0",  // another target's
      ".out.txt.tmp-" + dead + "-x",    // not a name this writer makes
      "out.txt.tmp-" + dead + "-0",     // not hidden
  };
  for (const auto& names : {stale, kept}) {
    for (const std::string& name : names) std::ofstream(dir_ / name) << "partial";
  }
  write_file_atomically(dir_ / "out.txt", [](std::ostream& os) { os << "new"; }, false);
  EXPECT_EQ(slurp(dir_ / "out.txt"), "new");
  for (const std::string& name : stale) EXPECT_FALSE(fs::exists(dir_ / name)) << name;
  for (const std::string& name : kept) EXPECT_TRUE(fs::exists(dir_ / name)) << name;
}
