#pragma once
/// \file error.h
/// The exceptions EdgeFront throws, and the always-on internal check.
///
/// A caller's mistake (invalid handle, unreadable file, non-finite coordinate, absurd option)
/// throws `InvalidInput` or `IoError` with a message a user can act on. A mesh whose topology an
/// algorithm cannot handle throws `TopologyError`. A broken internal invariant throws
/// `InternalError` with file and line (`EF_CHECK`); it is never a bare `assert`.

#include <stdexcept>
#include <string>

namespace edgefront {

/// Base of every exception EdgeFront throws.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A caller passed something the function cannot work with (bad handle, option, source, value).
class InvalidInput : public Error {
 public:
  using Error::Error;
};

/// A file could not be read or written, or its content is malformed. The message names the file
/// and, where known, the line or element.
class IoError : public Error {
 public:
  using Error::Error;
};

/// The mesh has a topology the algorithm does not support (for example a non-manifold vertex).
class TopologyError : public Error {
 public:
  using Error::Error;
};

/// An internal invariant failed: a bug in EdgeFront, or a validator finding.
class InternalError : public Error {
 public:
  using Error::Error;
};

/// `value` as error messages print numbers: the shortest text that reads back exactly when it is
/// short ("0.5", "-3", "100000", "inf"), else two significant digits with a plain exponent
/// ("1.8e308" for DBL_MAX, "2.2e-308", "1.3e154"), never a 309-digit or a "0.000000".
std::string number_for_message(double value);

namespace detail {
[[noreturn]] void throw_check_failure(const char* expr, const char* file, int line, const std::string& msg);
}  // namespace detail

}  // namespace edgefront

/// Always-on check (also in Release builds): throws `edgefront::InternalError` naming the
/// expression, file and line, and the message.
#define EF_CHECK(cond, msg)                                                              \
  do {                                                                                   \
    if (!(cond)) ::edgefront::detail::throw_check_failure(#cond, __FILE__, __LINE__, (msg)); \
  } while (false)
