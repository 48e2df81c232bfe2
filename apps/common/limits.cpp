#include "common/limits.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>

namespace impactkit::cli {

CLI::Validator AtMost(long long limit, const std::string& unit) {
  return CLI::Validator(
      [limit, unit](std::string& text) -> std::string {
        // Base 0, as CLI11 converts integers: "0x..." must not slip past.
        errno = 0;
        char* end = nullptr;
        const long long value = std::strtoll(text.c_str(), &end, 0);
        if (end == text.c_str() || *end != '\0') return "";  // not an integer: CLI11 says so
        const bool too_large = errno == ERANGE ? value > 0 : value > limit;
        if (!too_large) return "";
        return fmt::format("at most {} {}, got {}", limit, unit, text);
      },
      "");
}

CLI::Validator OutputPath(const std::string& noun) {
  return CLI::Validator(
      [noun](std::string& text) -> std::string {
        return text.empty() ? fmt::format("an empty path names no {}", noun) : "";
      },
      "");
}

}  // namespace impactkit::cli
