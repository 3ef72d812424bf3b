#include "edgefront/point_cloud_io.h"

#include <cmath>
#include <limits>
#include <string>

#include "detail/io_common.h"
#include "detail/mesh_parsers.h"
#include "edgefront/atomic_write.h"
#include "edgefront/coordinate_range.h"
#include "edgefront/error.h"

namespace edgefront {

namespace fs = std::filesystem;

namespace {

bool finite(const Vec3& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

/// Normalizes `n` in place; returns an error text or empty.
std::string normalize_normal(Vec3& n) {
  if (!finite(n)) return "non-finite normal";
  const double length = n.norm();
  if (std::isinf(length)) return "normal too long (its length overflows)";
  if (!(length > 0)) return n == Vec3(0, 0, 0) ? "zero-length normal" : "normal too short (its squared length underflows)";
  n /= length;
  return {};
}

// The normals of one file under PointReadOptions: checks and normalizes each, throws for an
// invalid one unless tolerated, then counts it and stores NaN.
struct NormalTally {
  const PointReadOptions& options;
  size_t total = 0, invalid = 0, zero = 0;
  std::string first;  // where and what the first invalid normal was

  // `what` and `index` name the line or vertex for messages ("line 3", "vertex 2"); the text is
  // made only for an invalid normal.
  template <class Fail>
  Vec3 take(Vec3 n, const char* what, size_t index, Fail&& fail) {
    ++total;
    const std::string problem = normalize_normal(n);
    if (problem.empty()) return n;
    if (!options.tolerate_invalid_normals) fail(problem);
    if (invalid++ == 0) first = std::string(what) + " " + std::to_string(index) + ": " + problem;
    if (n == Vec3(0, 0, 0)) ++zero;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return Vec3(nan, nan, nan);
  }

  // Clears the normals when none is valid; fills the report.
  void finish(PointCloud& cloud, bool had_normals, PointReadReport* report) const {
    const bool none_valid = total > 0 && invalid == total;
    if (none_valid) cloud.normals.clear();
    if (!report) return;
    report->points = cloud.size();
    report->invalid_normals = invalid;
    report->zero_normals = zero;
    report->all_normals_invalid = none_valid;
    report->normals_ignored = had_normals && options.ignore_normals;
    if (none_valid) {
      report->warning = zero == total ? "all " + std::to_string(total) + " normals are zero-length: the cloud is read without normals"
                                      : "none of the " + std::to_string(total) + " normals is valid (" +
                                            std::to_string(zero) + " zero-length, " + std::to_string(total - zero) +
                                            " NaN, infinite or too short/long): the cloud is read without normals";
    } else if (invalid > 0) {
      const std::string kinds =
          zero == invalid ? std::to_string(zero) + " zero-length"
          : zero == 0     ? std::to_string(invalid) + " NaN, infinite or too short/long"
                          : std::to_string(zero) + " zero-length, " + std::to_string(invalid - zero) +
                                " NaN, infinite or too short/long";
      report->warning = std::to_string(invalid) + " of " + std::to_string(total) + " normals are invalid (" + kinds +
                        ") and were dropped (first: " + first + ")";
    }
  }
};

PointCloud read_xyz(std::string_view data, const fs::path& file, NormalTally& tally, bool& had_normals) {
  data = detail::text_content(data, file, "a text point");
  PointCloud cloud;
  detail::LineReader lines(data);
  std::string_view line;
  std::vector<std::string_view> tokens;
  size_t per_line = 0, per_line_first = 0;
  bool have_count = false;
  uint64_t declared = 0;
  size_t count_line = 0;
  while (lines.next(line)) {
    line = detail::strip_comment(line);
    if (line.empty()) continue;
    detail::split_tokens(line, tokens);
    const size_t ln = lines.line_number();
    if (per_line == 0 && tokens.size() == 1 && !have_count && cloud.empty()) {
      if (!detail::parse_uint64(tokens[0], declared)) {
        detail::throw_io_line(
            file, ln,
            "expected 3 or 6 numbers (x y z [nx ny nz]), found 1 value " + detail::quote(tokens[0]));
      }
      have_count = true;
      count_line = ln;
      continue;
    }
    if (per_line == 0) {
      if (tokens.size() != 3 && tokens.size() != 6) {
        detail::throw_io_line(
            file, ln, "expected 3 or 6 numbers (x y z [nx ny nz]), found " + std::to_string(tokens.size()));
      }
      per_line = tokens.size();
      per_line_first = ln;
    } else if (tokens.size() != per_line) {
      detail::throw_io_line(file, ln,
                            "expected " + std::to_string(per_line) + " numbers like line " +
                                std::to_string(per_line_first) + ", found " + std::to_string(tokens.size()));
    }
    double v[6];
    const size_t parsed = tally.options.ignore_normals ? 3 : per_line;
    for (size_t k = 0; k < parsed; ++k) {
      if (!detail::parse_double(tokens[k], v[k]))
        detail::throw_io_line(file, ln, detail::bad_number(tokens[k]));
    }
    const Vec3 p(v[0], v[1], v[2]);
    if (!finite(p)) detail::throw_io_line(file, ln, "non-finite coordinate");
    cloud.points.push_back(p);
    if (per_line == 6 && !tally.options.ignore_normals) {
      cloud.normals.push_back(tally.take(Vec3(v[3], v[4], v[5]), "line", ln,
                                         [&](const std::string& problem) { detail::throw_io_line(file, ln, problem); }));
    }
  }
  if (have_count && declared != cloud.size()) {
    detail::throw_io_line(
        file, count_line,
        "the file declares " + std::to_string(declared) + " points but has " + std::to_string(cloud.size()));
  }
  if (std::string why = coordinate_range_problem(cloud.points); !why.empty()) detail::throw_io(file, why);
  had_normals = per_line == 6;
  return cloud;
}

}  // namespace

namespace {

bool is_text_points(const std::string& ext) { return ext == ".xyz" || ext == ".txt" || ext == ".pts"; }

void check_points_extension(const fs::path& path, const std::string& ext) {
  if (!is_text_points(ext) && ext != ".ply" && ext != ".off" && ext != ".obj") {
    detail::throw_io(path, "unknown point file extension " + detail::quote(path.extension().string()) +
                               " (supported: .xyz, .txt, .pts, .ply, .off, .obj)");
  }
}

PointCloud parse_points(std::string_view data, const fs::path& path, const std::string& ext,
                        const PointReadOptions& read_options, PointReadReport* report) {
  if (data.empty()) detail::throw_io(path, "file is empty");
  PointCloud cloud;
  NormalTally tally{read_options, 0, 0, 0, {}};
  bool had_normals = false;
  if (is_text_points(ext)) {
    cloud = read_xyz(data, path, tally, had_normals);
  } else {
    detail::ParseOptions options;
    options.normals = ext == ".ply";
    detail::RawMesh raw = detail::parse_mesh_file(data, path, ext, options);
    had_normals = !raw.normals.empty();
    if (read_options.ignore_normals) raw.normals.clear();
    for (size_t i = 0; i < raw.normals.size(); ++i) {
      raw.normals[i] = tally.take(raw.normals[i], "vertex", i, [&](const std::string& problem) {
        detail::throw_io(path, "vertex " + std::to_string(i) + ": " + problem);
      });
    }
    cloud.points = std::move(raw.points);
    cloud.normals = std::move(raw.normals);
  }
  if (cloud.empty()) detail::throw_io(path, "the file contains no points");
  tally.finish(cloud, had_normals, report);
  return cloud;
}

}  // namespace

PointCloud read_points(const fs::path& path) {
  return read_points(path, {}, nullptr);
}

PointCloud read_points(const fs::path& path, const PointReadOptions& options, PointReadReport* report) {
  if (report) *report = {};
  const std::string ext = detail::lower_extension(path);
  check_points_extension(path, ext);
  const detail::FileContent content(path);
  return parse_points(content.view(), path, ext, options, report);
}

PointCloud read_points_from_buffer(std::string_view data, const fs::path& name) {
  return read_points_from_buffer(data, name, {}, nullptr);
}

PointCloud read_points_from_buffer(std::string_view data, const fs::path& name, const PointReadOptions& options,
                                   PointReadReport* report) {
  if (report) *report = {};
  const std::string ext = detail::lower_extension(name);
  check_points_extension(name, ext);
  return parse_points(data, name, ext, options, report);
}

void write_points(const PointCloud& cloud, const fs::path& path) {
  const std::string ext = detail::lower_extension(path);
  const bool text = ext == ".xyz" || ext == ".txt" || ext == ".pts";
  const std::string where = "write_points(" + path.string() + "): ";
  if (!text && ext != ".ply") {
    throw InvalidInput(where + "unsupported extension " + detail::quote(path.extension().string()) +
                       " (supported: .xyz, .txt, .pts, .ply)");
  }
  if (!cloud.normals.empty() && cloud.normals.size() != cloud.points.size()) {
    throw InvalidInput(where + "the cloud has " + std::to_string(cloud.points.size()) + " points but " +
                       std::to_string(cloud.normals.size()) + " normals");
  }
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    if (!finite(cloud.points[i]))
      throw InvalidInput(where + "point " + std::to_string(i) + " has a non-finite coordinate");
  }
  for (size_t i = 0; i < cloud.normals.size(); ++i) {
    if (!finite(cloud.normals[i]))
      throw InvalidInput(where + "normal " + std::to_string(i) + " is not finite");
  }
  const bool normals = cloud.has_normals();
  write_file_atomically(
      path,
      [&](std::ostream& os) {
        std::string b;
        const auto flush = [&](bool force) {
          if (force || b.size() >= (1u << 20)) {
            os.write(b.data(), static_cast<std::streamsize>(b.size()));
            b.clear();
          }
        };
        if (text) {
          for (size_t i = 0; i < cloud.size(); ++i) {
            const Vec3& p = cloud.points[i];
            for (int k = 0; k < 3; ++k) {
              if (k > 0) b += ' ';
              detail::append_double(b, p[k]);
            }
            if (normals) {
              for (int k = 0; k < 3; ++k) {
                b += ' ';
                detail::append_double(b, cloud.normals[i][k]);
              }
            }
            b += '\n';
            flush(false);
          }
        } else {
          b += "ply\nformat binary_little_endian 1.0\ncomment written by EdgeFront\n";
          b += "element vertex " + std::to_string(cloud.size()) + "\n";
          b += "property double x\nproperty double y\nproperty double z\n";
          if (normals) b += "property double nx\nproperty double ny\nproperty double nz\n";
          b += "end_header\n";
          for (size_t i = 0; i < cloud.size(); ++i) {
            for (int k = 0; k < 3; ++k) detail::append_le<double>(b, cloud.points[i][k]);
            if (normals) {
              for (int k = 0; k < 3; ++k) detail::append_le<double>(b, cloud.normals[i][k]);
            }
            flush(false);
          }
        }
        flush(true);
      },
      !text);
}

}  // namespace edgefront
