#pragma once
// Running the built command-line tools from tests: a real process, its exit code and output.

#include <sys/wait.h>

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

}  // namespace eftest
