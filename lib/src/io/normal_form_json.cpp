#include "io/normal_form_json.hpp"

#include <vector>

#include "impactkit/io/branch_output.hpp"

namespace impactkit {
namespace {

template <typename Vector>
std::vector<double> Values(const Vector& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace

nlohmann::json PredictionJson(const GrazingPrediction& prediction) {
  nlohmann::json attractors = nlohmann::json::array();
  for (const LocalAttractor& a : prediction.attractors) {
    attractors.push_back({{"distance", a.distance},
                          {"period", a.period},
                          {"contacts", a.contacts},
                          {"extent", a.extent},
                          {"lyapunov", a.lyapunov},
                          {"motion", a.motion},
                          {"within_reach", a.within_reach}});
  }
  return {{"side", prediction.side},
          {"local", prediction.local},
          {"unstable_grazing_orbit", prediction.unstable_grazing_orbit},
          {"motion", prediction.motion},
          {"scenario", prediction.scenario},
          {"distance", prediction.distance},
          {"one_dimensional", prediction.one_dimensional.empty()
                                  ? nlohmann::json(nullptr)
                                  : nlohmann::json(prediction.one_dimensional)},
          {"description", prediction.Describe()},
          {"attractors", attractors}};
}

nlohmann::json NormalFormJson(const GrazingNormalForm& form) {
  nlohmann::json linear = nlohmann::json::array();
  for (Eigen::Index i = 0; i < form.linear.rows(); ++i) {
    linear.push_back(Values(Eigen::RowVectorXd(form.linear.row(i))));
  }
  nlohmann::json eigenvalues = nlohmann::json::array();
  for (const std::complex<double>& lambda : form.eigenvalues) {
    eigenvalues.push_back({lambda.real(), lambda.imag()});
  }
  nlohmann::json j = {{"parameter", form.parameter},
                      {"param", form.parameter_value},
                      {"stop", form.stop + 1},
                      {"p", form.p},
                      {"q", form.q},
                      {"releases", form.releases},
                      {"time", form.time},
                      {"phase", form.phase},
                      {"touch", Values(form.touch)},
                      {"linear", linear},
                      {"eigenvalues", eigenvalues},
                      {"normal", Values(form.normal)},
                      {"curvature", form.curvature},
                      {"root", Values(form.root)},
                      {"unfolding", form.unfolding},
                      {"reach", form.reach},
                      {"reach_bounded", form.reach_bounded}};
  if (form.reduced) {
    const SquareRootReduction& r = *form.reduced;
    j["reduced"] = {{"lambda", r.lambda},
                    {"kappa", r.kappa},
                    {"s", r.s},
                    {"break_rate", r.break_rate},
                    {"dominance", r.dominance}};
  } else {
    j["reduced"] = nullptr;
    j["reduction_note"] = form.reduction_note;
  }
  if (form.prediction) j["prediction"] = PredictionJson(*form.prediction);
  return j;
}

std::string GrazingNormalFormJson(const GrazingNormalForm& form) {
  return NormalFormJson(form).dump();
}

void AddNormalForm(const std::optional<GrazingNormalForm>& form, const std::string& note,
                   nlohmann::json* j) {
  if (form) {
    (*j)["normal_form"] = NormalFormJson(*form);
  } else {
    (*j)["normal_form"] = nullptr;
    (*j)["normal_form_note"] = note;
  }
}

}  // namespace impactkit
