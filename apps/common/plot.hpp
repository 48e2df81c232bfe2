#pragma once
/// \file common/plot.hpp
/// Line charts through gnuplot: the data and a script go to a private
/// temporary directory, gnuplot renders the image there, and the bytes come
/// back to the caller, who writes them like any other output (whole or not
/// at all). The output's extension names the format: PNG (pngcairo when
/// gnuplot has it, else the plain png terminal), or the vector formats a
/// journal takes, PDF (pdfcairo) and SVG. Each PNG records the version and
/// the command that drew it in an iTXt chunk with the keyword "Description"
/// (what image viewers and PIL's `Image.info` show), each SVG in its
/// <desc> element; a PDF does not (gnuplot sets no PDF metadata).
///
/// With IMPACTKIT_PLOT_SOURCE=DIR in the environment, each figure's script
/// and data are also copied into DIR/<n>/ (n = 1, 2, ... per figure): a
/// self-contained gnuplot source to edit a figure for publication
/// (`cd DIR/1 && gnuplot chart.gp`).

#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace impactkit::cli {

/// gnuplot is missing or failed; the message says which, on one line.
class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The format of a figure, named by its file's extension.
enum class ImageFormat { kPng, kPdf, kSvg };

/// The format `path`'s extension names: .png, .pdf or .svg, in any case.
/// Throws InvalidInput for any other, naming the three.
ImageFormat ImageFormatOf(const std::filesystem::path& path);

/// A data set of a chart. A curve without data is drawn only in the key:
/// a legend entry that stands for several curves (a branch's stretches,
/// "stable" for every solid line).
struct Curve {
  std::string title;
  std::vector<double> x;
  std::vector<double> y;
  bool dashed = false;
  std::string color = "#000000";  ///< gnuplot colour, "#rrggbb"
  /// Draw each (x, y) as a dot, unjoined (bifurcation diagrams), of this
  /// gnuplot point size (small for dense data, larger for marked points).
  bool points = false;
  double point_size = 0.2;
  int point_type = 7;  ///< gnuplot pointtype: 7 filled circle, 5 square, 9 triangle, ...
};

/// The k-th of 20 colours that stay apart on white and from each other
/// (matplotlib's tab10, then the darker tab20b/c hues), repeating after 20.
std::string DistinctColor(std::size_t k);

/// A constant y across the chart (a stop, a threshold).
struct HorizontalLine {
  double y = 0.0;
  std::string title;
};

/// A text beside a point of the chart (a located special point).
struct PointLabel {
  double x = 0.0;
  double y = 0.0;
  std::string text;
};

struct LineChart {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<Curve> curves;
  std::vector<HorizontalLine> lines;
  /// The x axis's range; unset: the data's (panels of one figure share it).
  std::optional<std::array<double, 2>> x_range;
  /// y starts at 0 (max - min, amplitudes: never negative).
  bool y_from_zero = false;
  std::vector<PointLabel> labels;
  /// The key in a column right of the plot rather than in the panel: for a
  /// key of many entries (a diagram's families), which would hide data.
  bool key_outside = false;
  int width = 1000;  ///< pixels (points in a PDF)
  int height = 600;
};

/// A parameter's name as an axis label: the forcing frequency is Ω in
/// every figure, as in the paper; other parameters keep their names.
std::string ParameterLabel(std::string_view parameter);

/// Throws PlotError unless gnuplot is on PATH: call it before a long run
/// so that a missing gnuplot is reported before the work, not after.
void RequireGnuplot();

/// The chart as the bytes of a `format` image. Throws PlotError.
std::string RenderChart(const LineChart& chart, ImageFormat format);

/// A grid of cells coloured by class (a parameter map, a basin picture),
/// with a legend that names every class: outside on the right, in as many
/// columns as it takes, so that 30 or more classes stay readable.
struct ClassMap {
  std::string title;
  std::string x_label;
  std::string y_label;
  /// One (x, y) per cell on a regular grid, with its class in [0, names).
  std::vector<double> x;
  std::vector<double> y;
  std::vector<int> cell_class;
  std::vector<std::string> names;   ///< per class, in legend order
  std::vector<std::string> colors;  ///< per class, "#rrggbb"
  std::vector<Curve> overlays;      ///< drawn over the cells (curves of `impactkit curve`)
  int width = 1200;                 ///< pixels (points in a PDF)
  int height = 800;
};

/// The map as the bytes of a `format` image. Throws PlotError.
std::string RenderClassMap(const ClassMap& map, ImageFormat format);

/// Several charts stacked top to bottom in one image of width x height
/// pixels (the charts' own sizes are ignored), as the bytes of a `format`
/// image. Throws PlotError.
std::string RenderStacked(const std::vector<LineChart>& charts, int width, int height,
                          ImageFormat format);

}  // namespace impactkit::cli
