#pragma once
/// \file app_util.h
/// Shared by the command-line tools: parse the command line with CLI11, run the body, turn
/// exceptions into one line on stderr and an exit code.
///
/// Exit codes: 0 success (also for --help), 1 error (an exception from the body), 2 usage error
/// (CLI11 parse failure or an AppUsageError thrown by the body). Running out of memory is an
/// error naming the request ("--points 100000000: not enough memory ...").
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

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <iostream>
#include <new>
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

/// Prints "<app>: error: <request>: not enough memory ..." and returns 1.
inline int print_out_of_memory(const std::string& app_name, const std::string& request) {
  print_error(app_name, (request.empty() ? std::string() : request + ": ") +
                            "not enough memory for this request (the machine could not give what it needs: ask for "
                            "less)");
  return 1;
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

/// The request as given, for the message when memory runs out: each option of `sized` the
/// command line gave ("--points 100000000"), a file also with its size ("MESH big.ply (2.1 GB)").
inline std::string describe_request(const CLI::App& app, std::initializer_list<const char*> sized) {
  std::string out;
  for (const char* name : sized) {
    const CLI::Option* option = app.get_option_no_throw(name);
    if (option == nullptr || option->count() == 0) continue;
    for (const std::string& value : option->results()) {
      std::string item = option->get_name() + " " + value;
      std::error_code ec;
      const auto bytes = std::filesystem::is_regular_file(value, ec) ? std::filesystem::file_size(value, ec) : 0;
      if (!ec && bytes > 0) item += " (" + std::to_string((bytes + 500000) / 1000000) + " MB)";
      out += (out.empty() ? "" : ", ") + item;
    }
  }
  return out;
}

/// Parses `argv` with `app`, then runs `body` (a callable returning the exit code, usually 0).
/// Draws (or redraws) a one-line progress bar on stderr: "LABEL [####      ] DETAIL", returning
/// the cursor to the line's start. Call it only when stderr is a terminal (isatty), and end the
/// line with a newline when the work is done.
inline void draw_progress_bar(const std::string& label, double fraction, const std::string& detail) {
  constexpr int kWidth = 40;
  const int filled = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * kWidth);
  std::fprintf(stderr, "\r%-16s [%s%s] %-36s", label.c_str(), std::string(static_cast<size_t>(filled), '#').c_str(),
               std::string(static_cast<size_t>(kWidth - filled), ' ').c_str(), detail.c_str());
  std::fflush(stderr);
}

/// --help prints the help on stdout and returns 0; a parse error (an empty argument included)
/// prints one line and a hint on stderr and returns 2; an exception from `body` prints one line
/// and returns 1 (2 for AppUsageError). `sized` names the options (and positional files) whose
/// values decide how much memory the work takes: when it runs out (std::bad_alloc, or a size
/// beyond what a container can hold) the message names them as given.
template <class Body>
int run_app(CLI::App& app, int argc, char** argv, Body&& body, std::initializer_list<const char*> sized = {}) {
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
  } catch (const std::bad_alloc&) {
    return print_out_of_memory(name, describe_request(app, sized));
  } catch (const std::length_error&) {
    return print_out_of_memory(name, describe_request(app, sized));
  } catch (const std::exception& e) {
    print_error(name, e.what());
    return 1;
  } catch (...) {
    print_error(name, "unknown error");
    return 1;
  }
}

}  // namespace edgefront::apps
