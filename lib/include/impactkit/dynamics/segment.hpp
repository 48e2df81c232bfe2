#pragma once
/// \file segment.hpp
/// A piece of exact motion between two events, as the simulator hands it to
/// observers: the closed-form flow is the dense output, so an observer can
/// sample it, take stroboscopic points or find extrema exactly.

#include <Eigen/Dense>
#include <vector>

#include "impactkit/dynamics/flow.hpp"

namespace impactkit {

/// What the masses at the stops do during a segment.
enum class SegmentMode {
  kFree,     ///< flight: the free flow of all N coordinates
  kChatter,  ///< the tail of a chatter sequence, from its last simulated impact to the
             ///< accumulation point: the mass is modelled at the stop (the other
             ///< masses follow the stuck subsystem) but not yet sticking
  kStuck,    ///< sticking: a mass held at its stop while the contact force presses it there
};

class Segment {
 public:
  /// `flow` moves the DOFs `moving` (all N in free flight); the others are
  /// held at rest at `held_positions` (size N, read where a DOF is held).
  /// The vectors must outlive the segment.
  Segment(const LinearFlow& flow, double t0, const Eigen::VectorXd& z0, double begin, double end,
          SegmentMode mode, const std::vector<int>& moving, const Eigen::VectorXd& held_positions);

  double Begin() const { return begin_; }
  double End() const { return end_; }
  SegmentMode Mode() const { return mode_; }
  /// Sticking (kStuck); a chatter tail is not.
  bool Stuck() const { return mode_ == SegmentMode::kStuck; }

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
  SegmentMode mode_;
  const std::vector<int>* moving_;
  const Eigen::VectorXd* held_positions_;
};

}  // namespace impactkit
