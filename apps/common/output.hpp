#pragma once
/// \file common/output.hpp
/// How every command writes its files: all of them in one OutputSet
/// (impactkit/io/output_set.hpp), each created as a temporary before any
/// work, so that a bad path fails first, and all moved into place together
/// at the end, so that a failure or an interruption changes no file.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "common/plot.hpp"
#include "impactkit/io/output_set.hpp"

namespace impactkit::cli {

/// The file of `path` in `outputs`, created now; nullptr when `path` is
/// empty (the option was not given). Throws OutputError.
AtomicOutputFile* AddIfAsked(OutputSet& outputs, const std::filesystem::path& path);

/// Renders `chart` (RenderChart) into `file`, in the format its extension
/// names. Throws PlotError or OutputError.
void WriteChart(AtomicOutputFile& file, const LineChart& chart);

/// The check of a --plot FILE: a path whose extension names a format
/// (ImageFormatOf), so that a figure the tool cannot write is refused
/// before any work.
CLI::Validator FigurePath();

}  // namespace impactkit::cli
