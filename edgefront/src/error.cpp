#include "edgefront/error.h"

namespace edgefront::detail {

void throw_check_failure(const char* expr, const char* file, int line, const std::string& msg) {
  throw InternalError(std::string(file) + ":" + std::to_string(line) + ": check failed: " + expr +
                      (msg.empty() ? std::string() : ": " + msg));
}

}  // namespace edgefront::detail
