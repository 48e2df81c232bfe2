#include "impactkit/dynamics/segment.hpp"

#include <algorithm>

namespace impactkit {

Segment::Segment(const LinearFlow& flow, double t0, const Eigen::VectorXd& z0, double begin,
                 double end, SegmentMode mode, const std::vector<int>& moving,
                 const Eigen::VectorXd& held_positions)
    : flow_(&flow),
      t0_(t0),
      z0_(&z0),
      begin_(begin),
      end_(end),
      mode_(mode),
      moving_(&moving),
      held_positions_(&held_positions) {}

void Segment::StateAt(double t, Eigen::VectorXd* x, Eigen::VectorXd* v) const {
  if (static_cast<Eigen::Index>(moving_->size()) == held_positions_->size()) {
    flow_->State(t0_, *z0_, t, x, v);
    return;
  }
  Eigen::VectorXd xs, vs;
  flow_->State(t0_, *z0_, t, &xs, &vs);
  *x = *held_positions_;
  *v = Eigen::VectorXd::Zero(held_positions_->size());
  (*x)(*moving_) = xs;
  (*v)(*moving_) = vs;
}

Signal Segment::Position(int i) const {
  const int n = flow_->Dof();
  LinearOutput output{Eigen::RowVectorXd::Zero(n), Eigen::RowVectorXd::Zero(n), 0.0, 0.0};
  const auto at = std::find(moving_->begin(), moving_->end(), i);
  if (at == moving_->end()) {
    output.offset = (*held_positions_)(i);
  } else {
    output.wx(at - moving_->begin()) = 1.0;
  }
  return flow_->Output(flow_->Prepare(output), t0_, *z0_);
}

}  // namespace impactkit
