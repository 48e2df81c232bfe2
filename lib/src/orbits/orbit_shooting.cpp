#include "orbits/orbit_shooting.hpp"

#include <utility>

#include "dynamics/subsystem.hpp"

namespace impactkit {

ShootingProblem::ShootingProblem(const HybridSystem& hybrid, const ImpactMap& map,
                                 std::vector<int> stops, int q)
    : hybrid_(hybrid), map_(map), stops_(std::move(stops)), q_(q), n_(hybrid.GetSystem().Dof()) {}

Eigen::VectorXd ShootingProblem::Eta(const Eigen::VectorXd& z, int k) const {
  return z.segment(2 * n_ * k, 2 * n_);
}

Eigen::VectorXd ShootingProblem::Pack(const std::vector<Eigen::VectorXd>& etas) const {
  Eigen::VectorXd z(2 * n_ * Impacts());
  for (int k = 0; k < Impacts(); ++k) z.segment(2 * n_ * k, 2 * n_) = etas[k];
  return z;
}

Eigen::VectorXd ShootingProblem::WithPhase(Eigen::VectorXd z) const {
  const double tau = z(map_.TimeIndex());
  const double shift = hybrid_.GetSystem().Phase(tau) - tau;
  for (int k = 0; k < Impacts(); ++k) z(2 * n_ * k + map_.TimeIndex()) += shift;
  return z;
}

double ShootingProblem::EndTime(const Eigen::VectorXd& z, int k) const {
  const int next = (k + 1) % Impacts();
  const double shift = next == 0 ? q_ * hybrid_.GetSystem().ForcingPeriod() : 0.0;
  return z(2 * n_ * next + map_.TimeIndex()) + shift;
}

ShootingProblem::Flight ShootingProblem::Fly(const Eigen::VectorXd& z, int k,
                                             bool with_derivatives) const {
  const LinearFlow& flow = hybrid_.FreeFlow();
  const HybridState after = map_.Departure(Eta(z, k), stops_[k]);
  Flight flight;
  flight.end.t = EndTime(z, k);
  flow.StateFrom(after.t, after.x, after.v, flow.Transient(after.t, after.x, after.v), flight.end.t,
                 &flight.end.x, &flight.end.v);
  if (!with_derivatives) return flight;
  flight.g = map_.FlightJacobian(stops_[k], after, flight.end.t);
  flight.f = hybrid_.VectorField(flight.end.t, flight.end.x, flight.end.v);
  return flight;
}

bool ShootingProblem::Residual(const Eigen::VectorXd& z, Eigen::VectorXd* w) const {
  w->resize(z.size());
  for (int k = 0; k < Impacts(); ++k) {
    const int next = (k + 1) % Impacts();
    const Flight flight = Fly(z, k, false);
    const HybridState target = map_.ToState(Eta(z, next), stops_[next]);
    w->segment(2 * n_ * k, n_) = flight.end.x - target.x;
    w->segment(2 * n_ * k + n_, n_) = flight.end.v - target.v;
  }
  return w->allFinite();
}

bool ShootingProblem::Jacobian(const Eigen::VectorXd& z, Eigen::MatrixXd* jacobian) const {
  const int size = 2 * n_;
  jacobian->setZero(z.size(), z.size());
  for (int k = 0; k < Impacts(); ++k) {
    const int next = (k + 1) % Impacts();
    const Flight flight = Fly(z, k, true);
    // W_k depends on η_k through the flight, on η_{k+1} through the end
    // time (the flight's rate) and the target state.
    jacobian->block(size * k, size * k, size, size) += flight.g;
    auto by_next = jacobian->block(size * k, size * next, size, size);
    by_next -= map_.Embedding(stops_[next]);
    by_next.col(map_.TimeIndex()) += flight.f;
  }
  return jacobian->allFinite();
}

SolveSummary ShootingProblem::Solve(const NewtonOptions& options, Eigen::VectorXd* z) const {
  const impactkit::Residual residual = [this](const Eigen::VectorXd& x, Eigen::VectorXd* w) {
    return Residual(x, w);
  };
  const impactkit::Jacobian jacobian = [this](const Eigen::VectorXd& x, Eigen::MatrixXd* j) {
    return Jacobian(x, j);
  };
  SolveSummary summary = SolveNewton(residual, jacobian, options, z);
  if (summary.termination != Termination::kConverged) return summary;
  constexpr int kMaxPolishSteps = 3;  // quadratic convergence: one or two suffice
  Eigen::VectorXd w, next_w;
  Eigen::MatrixXd j;
  Residual(*z, &w);
  double norm = w.cwiseAbs().maxCoeff();
  for (int step = 0; step < kMaxPolishSteps && Jacobian(*z, &j); ++step) {
    const Eigen::VectorXd next = *z - j.partialPivLu().solve(w);
    if (!Residual(next, &next_w) || !(next_w.cwiseAbs().maxCoeff() < norm)) break;
    *z = next;
    w = next_w;
    norm = w.cwiseAbs().maxCoeff();
  }
  summary.residual_norm = norm;
  return summary;
}

Eigen::MatrixXd ShootingProblem::MapJacobian(const Eigen::VectorXd& z) const {
  Eigen::MatrixXd product = Eigen::MatrixXd::Identity(2 * n_, 2 * n_);
  for (int k = 0; k < Impacts(); ++k) {
    const Flight flight = Fly(z, k, true);
    product = map_.ArrivalJacobian(flight.g, stops_[(k + 1) % Impacts()], flight.end) * product;
  }
  return product;
}

}  // namespace impactkit
