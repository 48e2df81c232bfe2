#include "impactkit/io/curve_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "io/normal_form_json.hpp"

namespace impactkit {
namespace {

int Outside(const PeriodicOrbit& orbit) {
  return static_cast<int>(std::count_if(
      orbit.multipliers.begin(), orbit.multipliers.end(),
      [](const std::complex<double>& l) { return std::abs(l) > 1.0 + kOutsideUnitCircle; }));
}

bool HasOrbit(const CurvePoint& point) { return point.orbit.multipliers.size() > 0; }

nlohmann::json PointJson(const Curve& curve, const CurvePoint& point) {
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

std::string CurvesJson(const std::vector<Curve>& curves, const std::string& system_json) {
  nlohmann::json j;
  j["params"] = {curves.front().parameter, curves.front().parameter2};
  j["curves"] = nlohmann::json::array();
  j["codim2_points"] = nlohmann::json::array();
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const Curve& c = curves[k];
    nlohmann::json curve = {{"type", ToString(c.type)},
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
      nlohmann::json point = {{"type", ToString(s.type)},
                              {"curve", k},
                              {c.parameter, s.point.parameter},
                              {c.parameter2, s.point.parameter2},
                              {"defining_residual", s.defining_residual},
                              {"second_residual", s.second_residual},
                              {"description", s.Describe(c.parameter, c.parameter2)}};
      if (s.type == Codim2Type::kUserTest) point["user_test"] = s.user_test;
      if (s.normal_form || !s.normal_form_note.empty()) {
        AddNormalForm(s.normal_form, s.normal_form_note, &point);
      }
      j["codim2_points"].push_back(std::move(point));
    }
  }
  if (!system_json.empty()) j["system"] = nlohmann::json::parse(system_json);
  return j.dump();
}

std::vector<std::string> CurveColumns(const Curve& curve) {
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

void WriteCurveRows(CsvWriter& csv, const Curve& curve) {
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

}  // namespace impactkit
