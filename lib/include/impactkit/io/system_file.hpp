#pragma once
/// \file system_file.hpp
/// Systems in files, JSON or TOML (docs/system-files.md). Two forms:
///
///     the paper's uniform chain          a general system
///     { "chain": {"n": 2, "m": 1,        { "mass":      [[1,0],[0,1]],
///                 "k": 1, "c": 0.1},       "damping":   [[0.2,-0.1],[-0.1,0.1]],
///       "forcing": [0.5, 0],               "stiffness": [[2,-1],[-1,1]],
///       "omega": 1.0, "xs": 0.1,           "forcing": [0.5, 0], "omega": 1.0,
///       "r": 0.7 }                         "xs": 0.1, "r": 0.7, "contact_dof": 2 }
///
/// Every field is optional; a missing one takes the paper's value
/// (PaperSystem(): m = k = 1, c = 0.1, A = (0.5, 0, ..., 0), Ω = 1, xs = 0.1,
/// r = 0.7; in the general form a missing matrix is the paper chain's of the
/// same size, and the contact DOF the last), so `{}` is the paper's system.
/// Unknown keys are errors, so that a misspelt field cannot silently fall
/// back to its default.

#include <filesystem>
#include <string>
#include <string_view>

#include "impactkit/model/system.hpp"

namespace impactkit {

enum class SystemFileFormat { kJson, kToml };

/// Reads and validates a system file; the format follows the extension
/// (.json or .toml). Throws InvalidInput with a one-line message naming the
/// file, the field and what is allowed.
System ReadSystemFile(const std::filesystem::path& path);

/// Parses and validates the text of a system file; `source` names it in
/// error messages. Throws InvalidInput.
System ParseSystem(std::string_view text, SystemFileFormat format, std::string_view source);

/// The system in the JSON form ReadSystemFile reads back (the chain form
/// when the system is a uniform chain), so that an output can record
/// exactly what produced it.
std::string SystemToJson(const System& system);

}  // namespace impactkit
