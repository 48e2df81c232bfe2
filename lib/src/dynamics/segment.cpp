#include "impactkit/dynamics/segment.hpp"

#include "dynamics/subsystem.hpp"

namespace impactkit {

Segment::Segment(const LinearFlow& flow, double t0, const Eigen::VectorXd& z0, double begin,
                 double end, SegmentMode mode, int contact_dof, double stop)
    : flow_(&flow),
      t0_(t0),
      z0_(&z0),
      begin_(begin),
      end_(end),
      mode_(mode),
      contact_dof_(contact_dof),
      stop_(stop) {}

void Segment::StateAt(double t, Eigen::VectorXd* x, Eigen::VectorXd* v) const {
  if (mode_ == SegmentMode::kFree) {
    flow_->State(t0_, *z0_, t, x, v);
    return;
  }
  Eigen::VectorXd xs, vs;
  flow_->State(t0_, *z0_, t, &xs, &vs);
  *x = EmbedAtStop(xs, contact_dof_, stop_);
  *v = EmbedAtStop(vs, contact_dof_, 0.0);
}

Signal Segment::Position(int i) const {
  const int n = flow_->Dof();
  LinearOutput output{Eigen::RowVectorXd::Zero(n), Eigen::RowVectorXd::Zero(n), 0.0, 0.0};
  const bool held = mode_ != SegmentMode::kFree;
  if (held && i == contact_dof_) {
    output.offset = stop_;
  } else {
    output.wx(held && i > contact_dof_ ? i - 1 : i) = 1.0;
  }
  return flow_->Output(flow_->Prepare(output), t0_, *z0_);
}

}  // namespace impactkit
