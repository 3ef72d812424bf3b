#include "edgefront/error.h"

#include <charconv>
#include <cmath>

namespace edgefront {

std::string number_for_message(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (r.ec == std::errc() && r.ptr - buffer > 10) {
    r = std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, 2);
  }
  if (r.ec != std::errc()) return "?";
  std::string text(buffer, r.ptr);
  const size_t plus = text.find("e+");
  if (plus != std::string::npos) text.erase(plus + 1, 1);
  // "e-05" -> "e-5", "e07" -> "e7"
  const size_t e = text.find('e');
  if (e != std::string::npos) {
    size_t digits = e + 1 + (text[e + 1] == '-' ? 1 : 0);
    while (digits + 1 < text.size() && text[digits] == '0') text.erase(digits, 1);
  }
  return text;
}

}  // namespace edgefront

namespace edgefront::detail {

void throw_check_failure(const char* expr, const char* file, int line, const std::string& msg) {
  throw InternalError(std::string(file) + ":" + std::to_string(line) + ": check failed: " + expr +
                      (msg.empty() ? std::string() : ": " + msg));
}

}  // namespace edgefront::detail
