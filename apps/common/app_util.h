#pragma once
/// \file app_util.h
/// Shared by the command-line tools: parse the command line with CLI11, run the body, turn
/// exceptions into one line on stderr and an exit code.
///
/// Exit codes: 0 success (also for --help), 1 error (an exception from the body), 2 usage error
/// (CLI11 parse failure or an AppUsageError thrown by the body).
///
/// \code
///   int main(int argc, char** argv) {
///     CLI::App app{"Print statistics of a mesh", "ef-info"};
///     std::string input;
///     app.add_option("MESH", input, "mesh file")->required();
///     return edgefront::apps::run_app(app, argc, argv, [&] {
///       ... call the library, print ...
///       return 0;
///     });
///   }
/// \endcode

#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "edgefront/error.h"

namespace edgefront::apps {

/// Thrown by an app body for a usage problem CLI11 cannot see (e.g. a bad option combination
/// found later); reported like a parse error, exit code 2.
class AppUsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Prints "<app>: error: <message>" as one line on stderr (newlines in the message become "; ").
inline void print_error(const std::string& app_name, const std::string& message) {
  std::string line;
  line.reserve(message.size());
  for (const char c : message) {
    if (c == '\n') {
      if (!line.empty() && line.back() != ' ') line += "; ";
    } else if (c != '\r') {
      line += c;
    }
  }
  while (!line.empty() && (line.back() == ' ' || line.back() == ';')) line.pop_back();
  std::cerr << app_name << ": error: " << line << std::endl;
}

/// An empty argument ('' or --name=) is a usage error in every tool: CLI11 would give a numeric
/// option the value 0 for it (e.g. `--levels ''` ran 0 levels). Throws CLI::ValidationError.
inline void refuse_empty_arguments(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool empty_after_equals = arg.size() > 2 && arg.rfind("--", 0) == 0 && arg.back() == '=';
    if (!arg.empty() && !empty_after_equals) continue;
    const std::string after = empty_after_equals ? arg.substr(0, arg.size() - 1) : i > 1 ? argv[i - 1] : "";
    throw CLI::ValidationError("empty value" + (after.empty() ? std::string() : " for " + after));
  }
}

/// Parses `argv` with `app`, then runs `body` (a callable returning the exit code, usually 0).
/// --help prints the help on stdout and returns 0; a parse error (an empty argument included)
/// prints one line and a hint on stderr and returns 2; an exception from `body` prints one line
/// and returns 1 (2 for AppUsageError).
template <class Body>
int run_app(CLI::App& app, int argc, char** argv, Body&& body) {
  const std::string name = app.get_name().empty() ? std::string("app") : app.get_name();
  try {
    refuse_empty_arguments(argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return app.exit(e);  // --help, --version: prints to stdout
    }
    print_error(name, std::string(e.what()) + " (run with --help for usage)");
    return 2;
  }
  try {
    return body();
  } catch (const AppUsageError& e) {
    print_error(name, std::string(e.what()) + " (run with --help for usage)");
    return 2;
  } catch (const edgefront::Error& e) {
    print_error(name, e.what());
    return 1;
  } catch (const std::exception& e) {
    print_error(name, e.what());
    return 1;
  } catch (...) {
    print_error(name, "unknown error");
    return 1;
  }
}

}  // namespace edgefront::apps
