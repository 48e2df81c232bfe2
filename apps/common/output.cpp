#include "common/output.hpp"

#include "impactkit/io/output_file.hpp"

namespace impactkit::cli {

void WriteWhole(const std::filesystem::path& path, const std::string& bytes) {
  AtomicOutputFile file(path);
  file.Write(bytes);
  file.Commit();
}

void WriteChartPng(const std::filesystem::path& path, const LineChart& chart) {
  WriteWhole(path, RenderPng(chart));
}

}  // namespace impactkit::cli
