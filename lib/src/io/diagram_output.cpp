#include "impactkit/io/diagram_output.hpp"

#include <fmt/format.h>

#include <complex>
#include <nlohmann/json.hpp>

#include "impactkit/io/branch_output.hpp"
#include "io/normal_form_json.hpp"

namespace impactkit {
namespace {

std::vector<double> Complex(std::complex<double> z) { return {z.real(), z.imag()}; }

nlohmann::json NodeJson(const DiagramNode& node, std::size_t id) {
  nlohmann::json multipliers = nlohmann::json::array();
  for (const std::complex<double>& m : node.multipliers) multipliers.push_back(Complex(m));
  const Eigen::VectorXd& eta = node.point.orbit.eta;
  nlohmann::json j = {{"id", id},
                      {"type", node.Name()},
                      {"param", node.parameter},
                      {"p", node.p},
                      {"q", node.q},
                      {"branch", node.branch},
                      {"multiplier", Complex(node.multiplier)},
                      {"multipliers", multipliers},
                      {"monitor", node.monitor},
                      {"eta", std::vector<double>(eta.data(), eta.data() + eta.size())}};
  if (node.special == SpecialPointType::kUserTest) j["user_test"] = node.user_test;
  if (node.special == SpecialPointType::kGrazing || node.special == SpecialPointType::kSticking) {
    j["vanishing_impact"] = node.vanishing_impact < 0 ? nlohmann::json(nullptr)
                                                      : nlohmann::json(node.vanishing_impact + 1);
  }
  if (node.special == SpecialPointType::kGrazing) {
    AddNormalForm(node.normal_form, node.normal_form_note, &j);
  }
  return j;
}

nlohmann::json EdgeJson(const Diagram& diagram, const DiagramEdge& edge) {
  const Branch& branch = diagram.branches[edge.branch].branch;
  nlohmann::json points = nlohmann::json::array();
  for (std::size_t i = edge.first; i <= edge.last; ++i) {
    const PeriodicOrbit& orbit = branch.points[i].orbit;
    std::vector<double> v;
    for (const OrbitImpact& impact : LeadingImpacts(orbit)) v.push_back(impact.velocity);
    points.push_back({{"param", branch.points[i].parameter},
                      {"stable", orbit.stable},
                      {"velocity", v},
                      {"range_xN", orbit.contacts.Range()}});
  }
  return {{"from", edge.from},
          {"to", edge.to},
          {"branch", edge.branch},
          {"section", ToString(branch.section)},
          {"p", branch.p},
          {"q", branch.q},
          {"releases", branch.releases},
          {"points", points}};
}

}  // namespace

std::string BranchLabel(const Diagram& diagram, std::size_t k) {
  const DiagramBranch& b = diagram.branches[k];
  if (b.parent < 0) return k == 0 ? "main" : fmt::format("seed{}", k + 1);
  const SpecialPointType at = diagram.nodes[b.parent].special;
  const char* kind = at == SpecialPointType::kPeriodDoubling ? "pd"
                     : at == SpecialPointType::kBranchPoint  ? "bp"
                     : at == SpecialPointType::kPitchfork    ? "pf"
                                                             : "graze";
  return fmt::format("{}{}", kind, k);
}

std::string DiagramJson(const Diagram& diagram) {
  nlohmann::json j = {
      {"parameter", diagram.parameter},     {"termination", ToString(diagram.termination)},
      {"message", diagram.message},         {"seconds", diagram.seconds},
      {"nodes", nlohmann::json::array()},   {"edges", nlohmann::json::array()},
      {"branches", nlohmann::json::array()}};
  for (std::size_t k = 0; k < diagram.nodes.size(); ++k) {
    j["nodes"].push_back(NodeJson(diagram.nodes[k], k));
  }
  for (const DiagramEdge& edge : diagram.edges) j["edges"].push_back(EdgeJson(diagram, edge));
  for (std::size_t k = 0; k < diagram.branches.size(); ++k) {
    const DiagramBranch& b = diagram.branches[k];
    j["branches"].push_back(
        nlohmann::json::parse(BranchJson(b.branch, BranchLabel(diagram, k), b.origin)));
  }
  return j.dump();
}

}  // namespace impactkit
