#include "curve/output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "common/curves.hpp"

namespace impactkit::cli {
namespace {

int Outside(const PeriodicOrbit& orbit) {
  return static_cast<int>(std::count_if(
      orbit.multipliers.begin(), orbit.multipliers.end(),
      [](const std::complex<double>& l) { return std::abs(l) > 1.0 + kOutsideUnitCircle; }));
}

bool HasOrbit(const CurvePoint& point) { return point.orbit.multipliers.size() > 0; }

/// The curve's type as outputs name it.
std::string CurveName(const impactkit::Curve& curve) { return ToString(curve.type); }

/// "period_doubling of P(1,1)", "grazing of the non-impacting response".
std::string CurveTitle(const impactkit::Curve& curve) {
  return curve.p == 0 ? CurveName(curve) + " of the non-impacting response"
                      : fmt::format("{} of P({},{})", CurveName(curve), curve.p, curve.q);
}

nlohmann::json PointJson(const impactkit::Curve& curve, const CurvePoint& point) {
  nlohmann::json multipliers = nlohmann::json::array();
  for (const std::complex<double>& l : point.orbit.multipliers) {
    multipliers.push_back({l.real(), l.imag()});
  }
  // A point without an orbit (the response's grazing, a corner where the
  // impact vanishes) has no multipliers to count.
  const nlohmann::json outside =
      HasOrbit(point) ? nlohmann::json(Outside(point.orbit)) : nlohmann::json(nullptr);
  return {{curve.parameter, point.parameter},
          {curve.parameter2, point.parameter2},
          {"multipliers", multipliers},
          {"outside", outside}};
}

}  // namespace

nlohmann::json CurvesJson(const std::vector<impactkit::Curve>& curves,
                          const nlohmann::json& provenance, const std::string& system_json) {
  nlohmann::json j;
  j["provenance"] = provenance;
  j["params"] = {curves.front().parameter, curves.front().parameter2};
  j["curves"] = nlohmann::json::array();
  j["codim2_points"] = nlohmann::json::array();
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const impactkit::Curve& c = curves[k];
    nlohmann::json curve = {{"type", CurveName(c)},
                            {"p", c.p},
                            {"q", c.q},
                            {"params", {c.parameter, c.parameter2}},
                            {"begin_reason", ToString(c.begin)},
                            {"begin_message", c.begin_message},
                            {"end_reason", ToString(c.end)},
                            {"end_message", c.end_message},
                            {"seconds", c.seconds}};
    curve["points"] = nlohmann::json::array();
    for (const CurvePoint& point : c.points) curve["points"].push_back(PointJson(c, point));
    j["curves"].push_back(std::move(curve));
    for (const Codim2Point& s : c.codim2_points) {
      j["codim2_points"].push_back({{"type", ToString(s.type)},
                                    {"curve", k},
                                    {c.parameter, s.point.parameter},
                                    {c.parameter2, s.point.parameter2},
                                    {"defining_residual", s.defining_residual},
                                    {"second_residual", s.second_residual},
                                    {"description", s.Describe(c.parameter, c.parameter2)}});
    }
  }
  j["system"] = nlohmann::json::parse(system_json);
  return j;
}

std::vector<std::string> CurveColumns(const impactkit::Curve& curve) {
  std::vector<std::string> columns = {curve.parameter, curve.parameter2, "arclength"};
  // Every orbit of the curve has the same number; its end points may have none.
  const Eigen::Index n =
      std::max_element(curve.points.begin(), curve.points.end(),
                       [](const CurvePoint& a, const CurvePoint& b) {
                         return a.orbit.multipliers.size() < b.orbit.multipliers.size();
                       })
          ->orbit.multipliers.size();
  for (Eigen::Index i = 1; i <= n; ++i) columns.push_back(fmt::format("mod{}", i));
  columns.push_back("outside");
  columns.push_back("codim2");
  return columns;
}

void WriteCurveRows(CsvWriter& csv, const impactkit::Curve& curve) {
  const std::size_t moduli = CurveColumns(curve).size() - 5;
  for (const CurvePoint& point : curve.points) {
    std::vector<double> row = {point.parameter, point.parameter2, point.arclength};
    std::vector<std::string> labels;
    if (HasOrbit(point)) {
      for (const std::complex<double>& l : point.orbit.multipliers) row.push_back(std::abs(l));
      row.push_back(Outside(point.orbit));
    } else {
      labels.assign(moduli + 1, "");  // empty cells: no multipliers to write
    }
    std::string label;
    for (const Codim2Point& s : curve.codim2_points) {
      if (s.point.arclength == point.arclength) label = ToString(s.type);
    }
    labels.push_back(label);
    csv.WriteRow(row, labels);
  }
}

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
  }
  fmt::print("  ends:     {} ({})\n", ToString(curve.end), curve.end_message);
}

}  // namespace impactkit::cli
