#pragma once
/// \file app_options.h
/// Option checks shared by the tools. They run as CLI11 validators, at parse time, before any
/// work or write: a bad value is a usage error (exit 2) naming the option.
///
/// Numbers are read strictly: the whole text, decimal; "nan" is refused everywhere; "-1" given
/// to a count or a seed is refused instead of wrapping around to 2^64 - 1; "1e400" is "out of the
/// range of a double", not "malformed"; bounds are printed readably ("1.8e308", never a
/// 309-digit number or "0.000000").
///
/// \code
///   app.add_option("--points", points, "...")->check(edgefront::apps::integer_range(1, 100000000));
///   app.add_option("--radius", radius, "...")->check(edgefront::apps::positive());
///   edgefront::apps::add_seed_option(app, "--seed", seed, "sampling seed");
///   app.add_option("-o", output, "...")->check(edgefront::apps::output_file({".off", ".ply"}));
/// \endcode

#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

#include "app_output.h"
#include "edgefront/parallel.h"
#include "app_parse.h"
#include "edgefront/error.h"

namespace edgefront::apps {

namespace detail {

/// `text` quoted for a message.
inline std::string quoted(const std::string& text) { return "'" + text + "'"; }

/// The bounds for a message: "1 ... 1e8", ">= 0", "<= 90".
inline std::string bounds_text(double lo, double hi) {
  if (lo == -std::numeric_limits<double>::max() || std::isinf(lo)) return "<= " + number_for_message(hi);
  if (hi == std::numeric_limits<double>::max() || std::isinf(hi)) return ">= " + number_for_message(lo);
  return number_for_message(lo) + " ... " + number_for_message(hi);
}

}  // namespace detail

/// A real number within [lo, hi]; NaN is refused, and so is infinity unless it is a bound.
inline CLI::Validator real_range(double lo, double hi) {
  const std::string bounds = detail::bounds_text(lo, hi);
  return CLI::Validator(
      [lo, hi, bounds](std::string& text) -> std::string {
        double value = 0;
        const char* end = text.data() + text.size();
        const char* first = text.data() + (!text.empty() && text.front() == '+' ? 1 : 0);
        const std::from_chars_result r = std::from_chars(first, end, value);
        if (r.ec == std::errc::result_out_of_range && r.ptr == end) {
          return detail::quoted(text) + " is out of the range of a double (+-" +
                 number_for_message(std::numeric_limits<double>::max()) + ")";
        }
        if (text.empty() || r.ec != std::errc() || r.ptr != end) return detail::quoted(text) + " is not a number";
        if (std::isnan(value)) return "nan is not a number (" + bounds + ")";
        if (!(value >= lo && value <= hi)) return text + " is out of range (" + bounds + ")";
        return {};
      },
      bounds);
}

/// A finite number >= 0.
inline CLI::Validator non_negative() { return real_range(0.0, std::numeric_limits<double>::max()); }

/// A finite number > 0.
inline CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::string problem = real_range(0.0, std::numeric_limits<double>::max())(text);
        if (!problem.empty()) return problem;
        if (std::stod(text) == 0.0) return "0 is out of range (> 0)";
        return {};
      },
      "> 0");
}

/// A decimal integer within [lo, hi] (no sign for lo >= 0: "-1" is refused, not wrapped).
inline CLI::Validator integer_range(long long lo, unsigned long long hi) {
  const std::string bounds = std::to_string(lo) + " ... " + std::to_string(hi);
  return CLI::Validator(
      [lo, hi, bounds](std::string& text) -> std::string {
        const bool negative = !text.empty() && text.front() == '-';
        const char* first = text.data() + (negative ? 1 : 0);
        const char* end = text.data() + text.size();
        unsigned long long magnitude = 0;
        const std::from_chars_result r = std::from_chars(first, end, magnitude);
        const bool digits = first != end && r.ptr == end && (r.ec == std::errc() || r.ec == std::errc::result_out_of_range);
        if (!digits) return detail::quoted(text) + " is not an integer";
        // -(lo + 1) + 1 is -lo without overflow (lo may be the smallest long long).
        const bool in_range =
            r.ec == std::errc() &&
            (negative ? lo < 0 && magnitude <= static_cast<unsigned long long>(-(lo + 1)) + 1
                      : magnitude <= hi && (lo <= 0 || magnitude >= static_cast<unsigned long long>(lo)));
        if (!in_range) return text + " is out of range (" + bounds + ")";
        return {};
      },
      bounds);
}

/// A comma-separated list of vertex indices ("0,5,12"), each a non-negative decimal integer.
/// Whether an index exists in the mesh is checked once the mesh is read ("out of range").
inline CLI::Validator index_list() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        for (const std::string& token : split_list(text, ',')) {
          if (token.empty() || token.find_first_not_of("0123456789") != std::string::npos) {
            return detail::quoted(text) + ": " + detail::quoted(token) + " is not a vertex index (a non-negative integer)";
          }
        }
        return {};
      },
      "V[,V...]");
}

/// A point on a face, "F:b0,b1,b2": a face index and three numbers (their validity as barycentric
/// coordinates, and the face's existence, are checked with the mesh).
inline CLI::Validator surface_point() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const size_t colon = text.find(':');
        if (colon == std::string::npos) return detail::quoted(text) + " is not F:b0,b1,b2";
        const std::string face = split_list(text.substr(0, colon), ':').front();
        if (face.empty() || face.find_first_not_of("0123456789") != std::string::npos) {
          return detail::quoted(text) + ": " + detail::quoted(face) + " is not a face index";
        }
        const std::vector<std::string> coordinates = split_list(text.substr(colon + 1), ',');
        if (coordinates.size() != 3) {
          return detail::quoted(text) + ": expected 3 barycentric coordinates, got " +
                 std::to_string(coordinates.size());
        }
        const CLI::Validator number =
            real_range(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
        for (std::string token : coordinates) {
          if (std::string problem = number(token); !problem.empty()) return detail::quoted(text) + ": " + problem;
        }
        return {};
      },
      "F:b0,b1,b2");
}

/// `--seed`-like option: an integer 0 ... 2^64 - 1 into `seed`.
inline CLI::Option* add_seed_option(CLI::App& app, const std::string& name, std::uint64_t& seed,
                                    const std::string& description) {
  return app.add_option(name, seed, description)
      ->check(integer_range(0, std::numeric_limits<std::uint64_t>::max()))
      ->capture_default_str();
}

/// `--threads N`: the threads an app's parallel work uses, 0 ... 4096; 0 (the default) = all
/// cores. Results do not depend on it (edgefront/parallel.h).
inline CLI::Option* add_threads_option(CLI::App& app, unsigned& threads) {
  return app.add_option("--threads", threads, "threads to use, 0 ... 4096 (default 0: all cores); the results are the "
                                              "same for any count")
      ->check(integer_range(0, edgefront::kMaxThreads));
}

/// An output file: its extension (lower case, with the dot) one of `extensions`, its directory
/// existing, and the path not a directory or another non-regular file.
inline CLI::Validator output_file(std::vector<std::string> extensions) {
  std::string list;
  for (const std::string& e : extensions) list += (list.empty() ? "" : ", ") + e;
  return CLI::Validator(
      [extensions, list](std::string& text) -> std::string {
        const std::filesystem::path path(text);
        const std::string ext = lower_extension(path);
        bool known = false;
        for (const std::string& e : extensions) known = known || e == ext;
        if (!known) return detail::quoted(text) + ": unsupported extension " + detail::quoted(ext) + " (use " + list + ")";
        std::error_code ec;
        const std::filesystem::path dir = path.parent_path();
        if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) {
          return detail::quoted(text) + ": the directory " + detail::quoted(dir.string()) + " does not exist";
        }
        const std::filesystem::file_status st = std::filesystem::status(path, ec);
        if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) {
          return detail::quoted(text) + " exists and is not a regular file";
        }
        return {};
      },
      "FILE(" + list + ")");
}

/// An existing directory.
inline CLI::Validator existing_directory() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::error_code ec;
        if (!std::filesystem::is_directory(text, ec)) return detail::quoted(text) + " is not a directory";
        return {};
      },
      "DIR");
}

}  // namespace edgefront::apps
