#include "held_torque_source.h"

#include <stdexcept>
#include <utility>

namespace idbench::internal {

HeldTorqueSource::HeldTorqueSource(std::unique_ptr<JointLogSource> source) : source_(std::move(source)) {
  if (!source_->layout().has_tau) {
    throw std::invalid_argument(source_->layout().source + ": torque_held: the log has no torque (or current) columns");
  }
}

const JointLogLayout& HeldTorqueSource::layout() const {
  layout_ = source_->layout();
  layout_.notes.push_back(layout_.source + ": torque held from each sample to the next (zero-order hold): each " +
                          "sample's torque read as the mean of its hold and the previous one's");
  return layout_;
}

bool HeldTorqueSource::Next(Eigen::Index max_samples, JointLogChunk* chunk) {
  if (!source_->Next(max_samples, chunk)) return false;
  Eigen::MatrixXd& tau = chunk->samples.tau;
  if (tau.rows() == 0) return true;
  const Eigen::RowVectorXd last = tau.row(tau.rows() - 1);
  // Each row with the one before it, from the last (so that each reads the torque as recorded).
  for (Eigen::Index k = tau.rows() - 1; k > 0; --k) tau.row(k) = 0.5 * (tau.row(k - 1) + tau.row(k));
  if (previous_.size() > 0) tau.row(0) = 0.5 * (previous_ + tau.row(0));
  previous_ = last;
  return true;
}

void HeldTorqueSource::Rewind() {
  source_->Rewind();
  previous_.resize(0);
}

}  // namespace idbench::internal
