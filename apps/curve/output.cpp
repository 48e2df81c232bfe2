#include "curve/output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "common/curves.hpp"

namespace impactkit::cli {
namespace {

/// The curve's type as outputs name it.
std::string CurveName(const impactkit::Curve& curve) { return ToString(curve.type); }

/// "period_doubling of P(1,1)", "grazing of the non-impacting response".
std::string CurveTitle(const impactkit::Curve& curve) {
  return curve.p == 0 ? CurveName(curve) + " of the non-impacting response"
                      : fmt::format("{} of P({},{})", CurveName(curve), curve.p, curve.q);
}

}  // namespace

LineChart CurveChart(const std::vector<impactkit::Curve>& curves) {
  static const std::map<SpecialPointType, std::pair<std::string, bool>> kStyle = {
      {SpecialPointType::kFold, {"#1f77b4", false}},
      {SpecialPointType::kPeriodDoubling, {"#d62728", false}},
      {SpecialPointType::kNeimarkSacker, {"#2ca02c", false}},
      {SpecialPointType::kGrazing, {"#000000", true}}};
  static const char* kMarks[] = {"#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"};
  LineChart chart;
  chart.title = "Two-parameter bifurcation curves";
  chart.x_label = ParameterLabel(curves.front().parameter);
  chart.y_label = ParameterLabel(curves.front().parameter2);
  std::map<std::string, Curve> marks;  // one legend entry per kind of codim-2 point
  for (const impactkit::Curve& c : curves) {
    Curve line;
    line.title = CurveKey(CurveName(c), c.p, c.q);
    std::tie(line.color, line.dashed) = kStyle.at(c.type);
    for (const CurvePoint& point : c.points) {
      line.x.push_back(point.parameter);
      line.y.push_back(point.parameter2);
    }
    chart.curves.push_back(std::move(line));
    for (const Codim2Point& s : c.codim2_points) {
      Curve& mark = marks[ToString(s.type)];
      mark.x.push_back(s.point.parameter);
      mark.y.push_back(s.point.parameter2);
      chart.labels.push_back({s.point.parameter, s.point.parameter2, ToString(s.type)});
    }
  }
  std::size_t k = 0;
  for (auto& [name, mark] : marks) {
    mark.title = name;
    mark.points = true;
    mark.point_size = 1.5;
    mark.color = kMarks[k++ % 5];
    chart.curves.push_back(std::move(mark));
  }
  return chart;
}

void PrintCurve(const impactkit::Curve& curve) {
  fmt::print("curve:      {} in ({}, {}): {} points, {:.2f} s\n", CurveTitle(curve),
             curve.parameter, curve.parameter2, curve.points.size(), curve.seconds);
  fmt::print("  begins:   {} ({})\n", ToString(curve.begin), curve.begin_message);
  for (const Codim2Point& s : curve.codim2_points) {
    fmt::print("  codim 2:  {}\n", s.Describe(curve.parameter, curve.parameter2));
    if (s.normal_form) fmt::print("            {}\n", s.normal_form->Describe());
    if (s.normal_form && s.normal_form->prediction) {
      fmt::print("            {}\n", s.normal_form->prediction->Describe());
    }
    if (!s.normal_form_note.empty()) {
      fmt::print("            no normal form: {}\n", s.normal_form_note);
    }
  }
  fmt::print("  ends:     {} ({})\n", ToString(curve.end), curve.end_message);
}

}  // namespace impactkit::cli
