#pragma once
// Running the built command-line tools from tests: a real process, its exit code and output.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace eftest {

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// 'text' for the shell (appended piecewise: GCC 12 warns -Wrestrict on "..." + std::string&&).
inline std::string shell_quoted(const std::string& text) {
  std::string q(1, '\'');
  q.append(text);
  q.push_back('\'');
  return q;
}

/// Runs `app args` with stdout and stderr captured through files in `dir`.
inline CommandResult run_command(const std::filesystem::path& app, const std::string& args,
                                 const std::filesystem::path& dir) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  std::string command = shell_quoted(app.string());
  command.append(" ").append(args).append(" >").append(shell_quoted(out.string()));
  command.append(" 2>").append(shell_quoted(err.string()));
  const int status = std::system(command.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

/// A fixture that runs one built app (EDGEFRONT_APP_DIR/<name>) in a fresh temporary directory
/// `dir_`, removed after the test. Derive: `class T : public AppTest { T() : AppTest("ef-x") {} };`
class AppTest : public ::testing::Test {
 protected:
  explicit AppTest(std::string name) : name_(std::move(name)) {}
  void SetUp() override {
    app_ = std::filesystem::path(EDGEFRONT_APP_DIR) / name_;
    ASSERT_TRUE(std::filesystem::exists(app_)) << name_ << " is not built at " << app_;
    dir_ = std::filesystem::temp_directory_path() /
           ("edgefront_" + name_ + "_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!dir_.empty()) std::filesystem::remove_all(dir_, ec);
  }
  CommandResult run(const std::string& args) const { return run_command(app_, args, dir_); }
  std::filesystem::path app_, dir_;

 private:
  std::string name_;
};

}  // namespace eftest
