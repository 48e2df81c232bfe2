#include "common/curves.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "impactkit/core/errors.hpp"

namespace impactkit::cli {

namespace {

/// The curves of one file in the plane, appended to `curves`.
void ReadCurveFile(const std::string& path, const std::string& x_name, const std::string& y_name,
                   std::vector<Curve>& curves) {
  std::ifstream in(path);
  Require(static_cast<bool>(in), fmt::format("cannot read curves file {}", path));
  try {
    const nlohmann::json json = nlohmann::json::parse(in);
    for (const nlohmann::json& curve : json.at("curves")) {
      const auto params = curve.at("params").get<std::vector<std::string>>();
      const bool in_plane = params.size() == 2 && ((params[0] == x_name && params[1] == y_name) ||
                                                   (params[0] == y_name && params[1] == x_name));
      if (!in_plane) continue;
      Curve line;
      line.title =
          CurveKey(curve.at("type").get<std::string>(), curve.value("p", 0), curve.value("q", 0));
      for (const nlohmann::json& point : curve.at("points")) {
        line.x.push_back(point.at(x_name).get<double>());
        line.y.push_back(point.at(y_name).get<double>());
      }
      curves.push_back(std::move(line));
    }
  } catch (const nlohmann::json::exception& error) {
    throw InvalidInput(fmt::format("curves file {}: {}", path, error.what()));
  }
}

}  // namespace

std::string CurveKey(std::string type, int p, int q) {
  if (type == "grazing" && p == 0) return "impact of P(1,q) vanishes";
  std::replace(type.begin(), type.end(), '_', ' ');
  return fmt::format("P({},{}) {}", p, q, type);
}

std::vector<Curve> ReadCurves(const std::vector<std::string>& paths, const std::string& x_name,
                              const std::string& y_name) {
  std::vector<Curve> curves;
  for (const std::string& path : paths) ReadCurveFile(path, x_name, y_name, curves);
  // Black and dark grey, solid and dashed, stand out on the map's colours
  // and from each other (the legend names each curve).
  for (std::size_t i = 0; i < curves.size(); ++i) {
    curves[i].color = i % 2 == 0 ? "#000000" : "#555555";
    curves[i].dashed = i % 4 >= 2;
  }
  return curves;
}

}  // namespace impactkit::cli
