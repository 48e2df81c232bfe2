#include "common/output.hpp"

#include "impactkit/core/errors.hpp"

namespace impactkit::cli {

AtomicOutputFile* AddIfAsked(OutputSet& outputs, const std::filesystem::path& path) {
  return path.empty() ? nullptr : &outputs.AddFile(path);
}

void WriteChart(AtomicOutputFile& file, const LineChart& chart) {
  file.Write(RenderChart(chart, ImageFormatOf(file.Path())));
}

CLI::Validator FigurePath() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          ImageFormatOf(text);
          return "";
        } catch (const InvalidInput& error) {
          return error.what();
        }
      },
      "");
}

}  // namespace impactkit::cli
