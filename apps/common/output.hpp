#pragma once
/// \file common/output.hpp
/// Writing a whole file at once, as every command writes its PNGs and
/// JSON: to a temporary file renamed over the target when complete, so that
/// a failure leaves no half-written file (impactkit/io/output_file.hpp).

#include <filesystem>
#include <string>

#include "common/plot.hpp"

namespace impactkit::cli {

/// Writes `bytes` to `path`, whole or not at all. Throws OutputError.
void WriteWhole(const std::filesystem::path& path, const std::string& bytes);

/// Renders `chart` (RenderPng) and writes it to `path`, whole or not at
/// all. Throws PlotError or OutputError.
void WriteChartPng(const std::filesystem::path& path, const LineChart& chart);

}  // namespace impactkit::cli
