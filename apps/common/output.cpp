#include "common/output.hpp"

namespace impactkit::cli {

AtomicOutputFile* AddIfAsked(OutputSet& outputs, const std::filesystem::path& path) {
  return path.empty() ? nullptr : &outputs.AddFile(path);
}

void WriteChartPng(AtomicOutputFile& file, const LineChart& chart) { file.Write(RenderPng(chart)); }

}  // namespace impactkit::cli
