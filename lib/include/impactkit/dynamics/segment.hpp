#pragma once
/// \file segment.hpp
/// A piece of exact motion between two events, as the simulator hands it to
/// observers: the closed-form flow is the dense output, so an observer can
/// sample it, take stroboscopic points or find extrema exactly.

#include <Eigen/Dense>

#include "impactkit/dynamics/flow.hpp"

namespace impactkit {

class Segment {
 public:
  /// `flow` is the free flow (n = N) or, when `stuck`, the stuck subsystem
  /// (n = N - 1, the contact DOF removed and held at `stop`).
  Segment(const LinearFlow& flow, double t0, const Eigen::VectorXd& z0, double begin, double end,
          bool stuck, int contact_dof, double stop);

  double Begin() const { return begin_; }
  double End() const { return end_; }
  bool Stuck() const { return stuck_; }

  /// Full positions and velocities (size N) at t in [Begin(), End()].
  void StateAt(double t, Eigen::VectorXd* x, Eigen::VectorXd* v) const;
  /// x_i(t) along the segment as a Signal (its derivative is v_i).
  Signal Position(int i) const;

 private:
  const LinearFlow* flow_;
  double t0_;
  const Eigen::VectorXd* z0_;
  double begin_;
  double end_;
  bool stuck_;
  int contact_dof_;
  double stop_;
};

}  // namespace impactkit
