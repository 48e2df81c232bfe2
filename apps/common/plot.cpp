#include "common/plot.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>

#include "common/provenance.hpp"
#include "impactkit/core/errors.hpp"

extern char** environ;  // POSIX: the environment gnuplot inherits

namespace impactkit::cli {
namespace {

namespace fs = std::filesystem;

/// A private directory, removed with its contents when it goes out of scope.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    std::string pattern = (fs::temp_directory_path() / "impactkit-plot-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw PlotError(
          fmt::format("cannot create a temporary directory for gnuplot: {}", std::strerror(errno)));
    }
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  fs::path operator/(std::string_view name) const { return path_ / name; }
  const fs::path& Path() const { return path_; }

 private:
  fs::path path_;
};

std::optional<fs::path> FindOnPath(std::string_view program) {
  const char* path = std::getenv("PATH");
  std::istringstream directories(path != nullptr ? path : "");
  for (std::string directory; std::getline(directories, directory, ':');) {
    const fs::path candidate = fs::path(directory.empty() ? "." : directory) / program;
    std::error_code error;
    if (fs::is_regular_file(candidate, error) && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  return std::nullopt;
}

void WriteFile(const fs::path& path, std::string_view contents) {
  std::ofstream out(path, std::ios::binary);
  out << contents;
  if (!out.flush()) throw PlotError(fmt::format("cannot write {}", path.string()));
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A gnuplot double-quoted string literal.
std::string Quoted(std::string_view text) {
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return quoted + "\"";
}

std::string CurveData(const Curve& curve) {
  std::string data;
  for (std::size_t i = 0; i < curve.x.size() && i < curve.y.size(); ++i) {
    fmt::format_to(std::back_inserter(data), "{} {}\n", curve.x[i], curve.y[i]);
  }
  return data;
}

/// Where a curve's points come from: its data file, or NaN for a curve
/// drawn only in the key.
std::string Source(const Curve& curve, const fs::path& file) {
  return curve.x.empty() ? "NaN" : Quoted(file.filename().string()) + " using 1:2";
}

/// One `plot` clause per curve (data in `files`, same order) and per line.
std::string PlotCommand(const LineChart& chart, const std::vector<fs::path>& files) {
  std::vector<std::string> clauses;
  for (std::size_t i = 0; i < chart.curves.size(); ++i) {
    const Curve& curve = chart.curves[i];
    const std::string title = curve.title.empty() ? "notitle" : "title " + Quoted(curve.title);
    if (curve.points) {
      clauses.push_back(fmt::format("{} with points pointtype {} pointsize {} linecolor rgb {} {}",
                                    Source(curve, files[i]), curve.point_type, curve.point_size,
                                    Quoted(curve.color), title));
      continue;
    }
    clauses.push_back(fmt::format("{} with lines dashtype {} linewidth {} linecolor rgb {} {}",
                                  Source(curve, files[i]), curve.dashed ? 2 : 1,
                                  curve.dashed ? 1.5 : 2.0, Quoted(curve.color), title));
  }
  for (const HorizontalLine& line : chart.lines) {
    clauses.push_back(
        fmt::format("{} with lines dashtype 3 linewidth 1.5 linecolor rgb \"#808080\" title {}",
                    line.y, Quoted(line.title)));
  }
  return fmt::format("plot {}\n", fmt::join(clauses, ", \\\n     "));
}

/// Each format with the extension that names it.
constexpr std::array<std::pair<ImageFormat, std::string_view>, 3> kExtensions = {
    {{ImageFormat::kPng, ".png"}, {ImageFormat::kPdf, ".pdf"}, {ImageFormat::kSvg, ".svg"}}};

/// `stem` with the extension of `format`: gnuplot's output file.
std::string ImageName(std::string_view stem, ImageFormat format) {
  const auto named = std::find_if(kExtensions.begin(), kExtensions.end(),
                                  [&](const auto& entry) { return entry.first == format; });
  return fmt::format("{}{}", stem, named->second);
}

/// The gnuplot terminal of `format` for a width x height pixel image.
std::string Terminal(ImageFormat format, int width, int height) {
  switch (format) {
    case ImageFormat::kPdf:
      // A point per pixel (cairo's 72 per inch): text and lines keep the
      // proportions of the PNG.
      return fmt::format("set terminal pdfcairo size {}in,{}in font \"Sans,11\" noenhanced\n",
                         width / 72.0, height / 72.0);
    case ImageFormat::kSvg:
      return fmt::format("set terminal svg size {},{} font \"Sans,11\" noenhanced\n", width,
                         height);
    case ImageFormat::kPng:
      break;
  }
  // pngcairo draws antialiased lines and real dashes; the gd-based png
  // terminal is the fallback that every gnuplot build has.
  return fmt::format(
      "if (strstrt(GPVAL_TERMINALS, \"pngcairo\") > 0) {{\n"
      "  set terminal pngcairo size {0},{1} font \"Sans,11\" noenhanced\n"
      "}} else {{\n"
      "  set terminal png size {0},{1} noenhanced\n"
      "}}\n",
      width, height);
}

/// The settings every chart shares: terminal, output, grid, key placement.
std::string Preamble(ImageFormat format, int width, int height, const fs::path& output,
                     std::string_view key) {
  return fmt::format(
      "set encoding utf8\n"
      "{}"
      "set output {}\n"
      "set grid\n"
      "set key {}\n",
      Terminal(format, width, height), Quoted(output.filename().string()), key);
}

/// gnuplot's first complaint, as the reason in our one-line error.
std::string FirstLine(const std::string& text) {
  const std::size_t start = text.find_first_not_of(" \t\r\n");
  if (start == std::string::npos) return "no message";
  return text.substr(start, text.find_first_of("\r\n", start) - start);
}

/// Runs gnuplot on `script` in the script's directory (the script names
/// its files relative to it), its output going to `log`. Throws PlotError.
void RunGnuplot(const fs::path& script, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, script.parent_path().c_str());
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::string program = "gnuplot", script_path = script.string();
  char* argv[] = {program.data(), script_path.data(), nullptr};
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    throw PlotError(fmt::format("cannot start gnuplot: {}", std::strerror(spawned)));
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw PlotError(fmt::format("gnuplot: {}", std::strerror(errno)));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw PlotError(fmt::format("gnuplot failed: {}", FirstLine(ReadFile(log))));
  }
}

/// The smallest and largest finite value of `values` over all curves.
template <typename Values>
std::optional<std::array<double, 2>> FiniteRange(const LineChart& chart, Values values) {
  std::optional<std::array<double, 2>> range;
  for (const Curve& curve : chart.curves) {
    for (double v : values(curve)) {
      if (!std::isfinite(v)) continue;
      if (!range) range = std::array{v, v};
      (*range)[0] = std::min((*range)[0], v);
      (*range)[1] = std::max((*range)[1], v);
    }
  }
  return range;
}

/// A range narrower than a few parts in 10^9 of its size is one value seen
/// through rounding; gnuplot would autoscale the noise, every tick label
/// reading the same digits. Such an axis is centred on the value and says so.
std::string AxisRange(char axis, const std::optional<std::array<double, 2>>& data) {
  if (!data) return fmt::format("set autoscale {0}\nset autoscale {0}fix\n", axis);
  const auto [low, high] = *data;
  const double size = std::max(std::abs(low), std::abs(high));
  if (high - low > 1e-9 * size && high > low) {
    return fmt::format("set autoscale {0}\nset autoscale {0}fix\n", axis);
  }
  const double middle = 0.5 * (low + high), half = std::max(0.05 * size, 1e-3);
  return fmt::format(
      "set {0}range [{1}:{2}]\n"
      "set label 1001 {3} at graph 0.02, graph {4} front\n",
      axis, middle - half, middle + half,
      Quoted(fmt::format("every {} value is {:.10g} (spread {:.1e})", axis, middle, high - low)),
      axis == 'x' ? 0.08 : 0.95);
}

/// The x and y ranges of one panel: fixed, from zero, or the data's.
std::string RangeSettings(const LineChart& chart) {
  std::string settings;
  if (chart.x_range) {
    settings += fmt::format("set xrange [{}:{}]\n", (*chart.x_range)[0], (*chart.x_range)[1]);
  } else {
    settings += AxisRange('x', FiniteRange(chart, [](const Curve& c) { return c.x; }));
  }
  // A margin keeps points off the frame (special points at a branch's end);
  // none below a y that starts at zero.
  const auto y = FiniteRange(chart, [](const Curve& c) { return c.y; });
  if (chart.y_from_zero && y && (*y)[1] > 0.0) {
    return settings + "set offsets graph 0.01, graph 0.01, graph 0.05, 0\nset yrange [0:*]\n";
  }
  return settings + "set offsets graph 0.01, graph 0.01, graph 0.05, graph 0.05\n" +
         AxisRange('y', y);
}

/// The settings and plot command of one chart of a multiplot.
std::string PanelScript(const LineChart& chart, const std::vector<fs::path>& files) {
  std::string labels = "unset label\n";
  for (const PointLabel& label : chart.labels) {
    labels += fmt::format("set label {} at {:.17g},{:.17g} offset 0.8,0.8 front\n",
                          Quoted(label.text), label.x, label.y);
  }
  const std::string key =
      chart.key_outside ? "set key outside right top vertical samplen 2 font \",9\"\n" : "";
  return fmt::format(
      "set title {}\n"
      "set xlabel {}\n"
      "set ylabel {}\n"
      "{}{}{}{}",
      Quoted(chart.title), Quoted(chart.x_label), Quoted(chart.y_label), key, labels,
      RangeSettings(chart), PlotCommand(chart, files));
}

/// The cells as "x y class" rows, for gnuplot's `with image`.
std::string CellData(const ClassMap& map) {
  std::string text;
  for (std::size_t i = 0; i < map.cell_class.size(); ++i) {
    text += fmt::format("{} {} {}\n", map.x[i], map.y[i], map.cell_class[i]);
  }
  return text;
}

/// The axis's range over the cells: from the first cell's edge to the
/// last's (`with image` draws each cell centred on its value, half a grid
/// step either side), so that the axis ends where the data do and no curve
/// drawn over the cells widens it into a blank band.
std::array<double, 2> CellRange(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  if (values.size() < 2) {
    const double half = std::max(0.05 * std::abs(values.front()), 0.5);
    return {values.front() - half, values.front() + half};
  }
  double step = values[1] - values[0];
  for (std::size_t i = 2; i < values.size(); ++i) step = std::min(step, values[i] - values[i - 1]);
  return {values.front() - step / 2, values.back() + step / 2};
}

/// A palette with one colour per class, and a legend entry per class (a
/// filled box drawn at NaN, so it shows only in the key).
std::string ClassMapScript(const ClassMap& map, const fs::path& cells,
                           const std::vector<fs::path>& overlays) {
  const int classes = static_cast<int>(map.names.size());
  std::vector<std::string> palette, keys;
  for (int c = 0; c < classes; ++c) {
    palette.push_back(fmt::format("{} \"{}\"", c, map.colors[c]));
    keys.push_back(fmt::format("NaN with boxes fillstyle solid 1.0 lc rgb \"{}\" title {}",
                               map.colors[c], Quoted(map.names[c])));
  }
  std::string plot =
      fmt::format("plot {} using 1:2:3 with image notitle", Quoted(cells.filename().string()));
  for (const std::string& key : keys) plot += ", " + key;
  // Each curve over a white halo: a dark line alone vanishes on dark cells.
  for (std::size_t i = 0; i < map.overlays.size(); ++i) {
    const Curve& curve = map.overlays[i];
    plot += fmt::format(
        ", {0} using 1:2 with lines lw 5 lc rgb \"#ffffff\" notitle"
        ", {0} using 1:2 with lines lw 2 dashtype {1} lc rgb \"{2}\" title {3}",
        Quoted(overlays[i].filename().string()), curve.dashed ? 2 : 1, curve.color,
        Quoted(curve.title));
  }
  // gnuplot's palette needs two colours: one class is drawn as if of two.
  if (classes == 1) palette.push_back(fmt::format("1 \"{}\"", map.colors[0]));
  const int colors = static_cast<int>(palette.size());
  const auto [x_low, x_high] = CellRange(map.x);
  const auto [y_low, y_high] = CellRange(map.y);
  return fmt::format(
      "set title {}\nset xlabel {}\nset ylabel {}\nunset grid\nunset colorbox\n"
      "set key outside right top vertical maxrows 32 samplen 1.5 font \",9\"\n"
      "set palette maxcolors {}\nset palette defined ({})\nset cbrange [-0.5:{}]\n"
      "set xrange [{:.17g}:{:.17g}]\nset yrange [{:.17g}:{:.17g}]\nset offsets 0, 0, 0, 0\n{}\n",
      Quoted(map.title), Quoted(map.x_label), Quoted(map.y_label), colors, fmt::join(palette, ", "),
      colors - 0.5, x_low, x_high, y_low, y_high, plot);
}

/// With IMPACTKIT_PLOT_SOURCE=DIR, the figure's script and data files go to
/// the first unused DIR/<n>/ as well (plot.hpp). Throws PlotError.
void KeepSource(const TemporaryDirectory& directory) {
  const char* keep = std::getenv("IMPACTKIT_PLOT_SOURCE");
  if (keep == nullptr || *keep == '\0') return;
  std::error_code error;
  fs::path target;
  for (int n = 1; target.empty(); ++n) {
    const fs::path candidate = fs::path(keep) / std::to_string(n);
    if (!fs::exists(candidate, error)) target = candidate;
  }
  fs::create_directories(target, error);
  for (const fs::directory_entry& entry : fs::directory_iterator(directory.Path(), error)) {
    const fs::path name = entry.path().filename();
    if (name.extension() == ".gp" || name.extension() == ".dat") {
      fs::copy_file(entry.path(), target / name, error);
    }
    if (error) break;
  }
  if (error) {
    throw PlotError(fmt::format("IMPACTKIT_PLOT_SOURCE: cannot copy the figure's source to {}: {}",
                                target.string(), error.message()));
  }
}

void AppendBigEndian(std::string& bytes, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((value >> shift) & 0xff);
}

/// `png` with an iTXt chunk (PNG 1.2, 11.3.4.5: UTF-8 text, uncompressed)
/// of `keyword` and `text` right after the IHDR chunk, which every PNG
/// starts with. The chunk's CRC is zlib's crc32, as PNG specifies.
std::string WithText(const std::string& png, std::string_view keyword, std::string_view text) {
  constexpr std::size_t kAfterHeader = 8 + 4 + 4 + 13 + 4;  // signature, IHDR chunk
  if (png.size() < kAfterHeader || png.compare(12, 4, "IHDR") != 0) {
    throw PlotError("gnuplot's image is not a PNG");
  }
  std::string chunk = "iTXt";
  chunk.append(keyword);
  chunk += std::string("\0\0\0\0\0", 5);  // keyword end, no compression, no language tags
  chunk.append(text);
  const auto* data = reinterpret_cast<const Bytef*>(chunk.data());
  const auto crc = static_cast<std::uint32_t>(::crc32(0L, data, static_cast<uInt>(chunk.size())));
  std::string out = png.substr(0, kAfterHeader);
  AppendBigEndian(out, static_cast<std::uint32_t>(chunk.size() - 4));
  out += chunk;
  AppendBigEndian(out, crc);
  return out + png.substr(kAfterHeader);
}

/// `text` with the characters XML gives a meaning escaped.
std::string XmlEscaped(std::string_view text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

/// `svg` with `text` as the description of the document: its first <desc>
/// element (gnuplot's "Produced by GNUPLOT ...") replaced.
std::string WithDescription(const std::string& svg, std::string_view text) {
  const std::size_t begin = svg.find("<desc>");
  const std::size_t end = svg.find("</desc>", begin);
  if (begin == std::string::npos || end == std::string::npos) {
    throw PlotError("gnuplot's SVG has no <desc> element");
  }
  return svg.substr(0, begin) + "<desc>" + XmlEscaped(text) + svg.substr(end);
}

/// Runs the script and returns its image, which records the command line
/// where the format has a place for it, keeping the source if asked.
std::string Render(const TemporaryDirectory& directory, const fs::path& script,
                   const fs::path& output, ImageFormat format) {
  RunGnuplot(script, directory / "gnuplot.log");
  std::string image = ReadFile(output);
  if (image.empty()) throw PlotError("gnuplot produced no image");
  KeepSource(directory);
  switch (format) {
    case ImageFormat::kPng:
      return WithText(image, "Description", CommandLineProvenance());
    case ImageFormat::kSvg:
      return WithDescription(image, CommandLineProvenance());
    case ImageFormat::kPdf:
      break;
  }
  return image;
}

}  // namespace

std::string DistinctColor(std::size_t k) {
  static constexpr std::array<const char*, 20> kColors = {
      "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
      "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#637939", "#8c6d31", "#843c39",
      "#7b4173", "#3182bd", "#e6550d", "#31a354", "#756bb1", "#636363"};
  return kColors[k % kColors.size()];
}

std::string ParameterLabel(std::string_view parameter) {
  return parameter == "omega" ? "Ω" : std::string(parameter);
}

ImageFormat ImageFormatOf(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const auto& [format, name] : kExtensions) {
    if (extension == name) return format;
  }
  throw InvalidInput(fmt::format(
      "{}: a figure is a .png, .pdf or .svg file (the extension names the format), not {}",
      path.string(), extension.empty() ? "a file without extension" : "'" + extension + "'"));
}

std::string RenderClassMap(const ClassMap& map, ImageFormat format) {
  RequireGnuplot();
  if (map.names.empty() || map.x.empty()) throw PlotError("a class map needs a cell and a class");
  const TemporaryDirectory directory;
  const fs::path image = directory / ImageName("map", format);
  const fs::path cells = directory / "cells.dat";
  WriteFile(cells, CellData(map));
  std::vector<fs::path> overlays;
  for (std::size_t i = 0; i < map.overlays.size(); ++i) {
    overlays.push_back(directory / fmt::format("overlay{}.dat", i + 1));
    WriteFile(overlays.back(), CurveData(map.overlays[i]));
  }
  const fs::path script_path = directory / "map.gp";
  WriteFile(script_path, Preamble(format, map.width, map.height, image, "outside right") +
                             ClassMapScript(map, cells, overlays));
  return Render(directory, script_path, image, format);
}

void RequireGnuplot() {
  if (!FindOnPath("gnuplot")) {
    throw PlotError(
        "gnuplot was not found on PATH; install it (Debian: gnuplot-nox) or leave out --plot");
  }
}

std::string RenderChart(const LineChart& chart, ImageFormat format) {
  return RenderStacked({chart}, chart.width, chart.height, format);
}

std::string RenderStacked(const std::vector<LineChart>& charts, int width, int height,
                          ImageFormat format) {
  RequireGnuplot();
  const TemporaryDirectory directory;
  const fs::path image = directory / ImageName("chart", format);
  const bool single = charts.size() == 1;
  // Below the plot, the key's height padded: gnuplot sets a bottom key's
  // row right against the x label otherwise, the label reading as an entry.
  std::string script =
      Preamble(format, width, height, image,
               single ? "outside bottom center horizontal height 1.5" : "top right");
  if (!single) script += fmt::format("set multiplot layout {},1\n", charts.size());
  for (std::size_t c = 0; c < charts.size(); ++c) {
    std::vector<fs::path> files;
    for (std::size_t i = 0; i < charts[c].curves.size(); ++i) {
      files.push_back(directory / fmt::format("chart{}-curve{}.dat", c + 1, i + 1));
      WriteFile(files.back(), CurveData(charts[c].curves[i]));
    }
    script += PanelScript(charts[c], files);
  }
  if (!single) script += "unset multiplot\n";
  const fs::path script_path = directory / "chart.gp";
  WriteFile(script_path, script);
  return Render(directory, script_path, image, format);
}

}  // namespace impactkit::cli
