#pragma once
/// \file app_parse.h
/// Parsing of element indices given on the command line (vertex and face handles), shared by
/// the tools. Every error names the option and the offending token.

#include <charconv>
#include <string>
#include <system_error>
#include <vector>

#include "app_util.h"
#include "edgefront/error.h"
#include "edgefront/mesh.h"

namespace edgefront::apps {

/// Splits `text` at every `sep`, trimming blanks and tabs around each piece; empty pieces stay
/// (so "0,,2" yields an empty token that the index parser rejects).
inline std::vector<std::string> split_list(const std::string& text, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t at = text.find(sep, start);
    const std::string token = text.substr(start, at == std::string::npos ? std::string::npos : at - start);
    const size_t first = token.find_first_not_of(" \t");
    const size_t last = token.find_last_not_of(" \t");
    out.push_back(first == std::string::npos ? std::string() : token.substr(first, last - first + 1));
    if (at == std::string::npos) break;
    start = at + 1;
  }
  return out;
}

/// Parses a non-negative index below `count`. `what` is the element's name in the singular
/// ("vertex", "face"), `whats` its plural.
/// \throws AppUsageError "<option>: '<token>' is not a <what> index ..." (not a number: exit 2) or
///         edgefront::InvalidInput "<option>: <what> <token> is out of range (the mesh has N <whats>)".
inline size_t parse_index(const std::string& token, size_t count, const std::string& option, const std::string& what,
                          const std::string& whats) {
  unsigned long long value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (token.empty() || ec == std::errc::invalid_argument || ptr != end) {
    throw AppUsageError(option + ": '" + token + "' is not a " + what + " index (a non-negative integer)");
  }
  if (ec == std::errc::result_out_of_range || value >= count) {
    throw InvalidInput(option + ": " + what + " " + token + " is out of range (the mesh has " + std::to_string(count) +
                       " " + (count == 1 ? what : whats) + ")");
  }
  return static_cast<size_t>(value);
}

/// Parses one vertex index of `mesh`-sized range `n_vertices`.
inline VertexHandle parse_vertex(const std::string& token, size_t n_vertices, const std::string& option) {
  return VertexHandle(static_cast<int>(parse_index(token, n_vertices, option, "vertex", "vertices")));
}

/// Parses a comma-separated list of vertex indices.
inline std::vector<VertexHandle> parse_vertex_list(const std::string& text, size_t n_vertices,
                                                   const std::string& option) {
  std::vector<VertexHandle> out;
  for (const std::string& token : split_list(text, ',')) out.push_back(parse_vertex(token, n_vertices, option));
  return out;
}

}  // namespace edgefront::apps
