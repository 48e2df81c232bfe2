#pragma once
/// \file toml_json.hpp
/// TOML documents as JSON values: system files come in both syntaxes, and
/// converting TOML's tree to JSON's lets one schema reader serve both.

#include <nlohmann/json.hpp>
#include <string_view>

namespace impactkit {

/// Parses a TOML document into the equivalent JSON value (tables become
/// objects, integers stay integers). Throws InvalidInput naming `source`,
/// line and column for a syntax error or a date/time value.
nlohmann::json ParseTomlAsJson(std::string_view text, std::string_view source);

}  // namespace impactkit
