#include "io/toml_json.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <string>

#include "impactkit/model/system.hpp"

namespace impactkit {
namespace {

std::string Location(std::string_view source, const toml::source_region& region) {
  return fmt::format("{}:{}:{}", source, region.begin.line, region.begin.column);
}

nlohmann::json ToJson(const toml::node& node, std::string_view source) {
  if (const toml::table* table = node.as_table()) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& [key, value] : *table) object[std::string(key.str())] = ToJson(value, source);
    return object;
  }
  if (const toml::array* array = node.as_array()) {
    nlohmann::json list = nlohmann::json::array();
    for (const toml::node& element : *array) list.push_back(ToJson(element, source));
    return list;
  }
  if (const auto* integer = node.as_integer()) return integer->get();
  if (const auto* floating = node.as_floating_point()) return floating->get();
  if (const auto* boolean = node.as_boolean()) return boolean->get();
  if (const auto* string = node.as_string()) return string->get();
  throw InvalidInput(fmt::format("{}: dates and times have no meaning in a system file",
                                 Location(source, node.source())));
}

}  // namespace

nlohmann::json ParseTomlAsJson(std::string_view text, std::string_view source) {
  try {
    return ToJson(toml::parse(text, source), source);
  } catch (const toml::parse_error& error) {
    std::string description(error.description());
    std::replace(description.begin(), description.end(), '\n', ' ');
    throw InvalidInput(
        fmt::format("{}: invalid TOML: {}", Location(source, error.source()), description));
  }
}

}  // namespace impactkit
