#include "idbench/logs/overlap_windows.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace idbench {

OverlapWindows::OverlapWindows(Eigen::Index n_total, Eigen::Index n_cols, Eigen::Index margin, Eigen::Index block)
    : n_total_(n_total), margin_(margin), block_(block) {
  if (n_total < 1 || margin < 0 || block < 1 || n_cols < 1) {
    throw std::invalid_argument("overlap windows: expected n_total >= 1, n_cols >= 1, margin >= 0, block >= 1, got " +
                                std::to_string(n_total) + ", " + std::to_string(n_cols) + ", " +
                                std::to_string(margin) + ", " + std::to_string(block));
  }
  buffer_.resize(std::min(n_total, block + 2 * margin), n_cols);
}

void OverlapWindows::Push(Eigen::Ref<const Eigen::MatrixXd> rows, const Process& process) {
  if (rows.cols() != buffer_.cols() || n_pushed() + rows.rows() > n_total_) {
    throw std::invalid_argument("overlap windows: expected at most " + std::to_string(n_total_ - n_pushed()) +
                                " rows of " + std::to_string(buffer_.cols()) + " columns, got " +
                                std::to_string(rows.rows()) + " x " + std::to_string(rows.cols()));
  }
  Eigen::Index taken = 0;
  for (;;) {
    // Fill the buffer up to its capacity.
    const Eigen::Index m = std::min(rows.rows() - taken, buffer_.rows() - held_);
    buffer_.middleRows(held_, m) = rows.middleRows(taken, m);
    held_ += m;
    taken += m;
    // Hand on every block whose window is complete.
    while (!done()) {
      const Eigen::Index o0 = next_out_, o1 = std::min(n_total_, o0 + block_);
      const Eigen::Index w0 = std::max<Eigen::Index>(0, o0 - margin_), w1 = std::min(n_total_, o1 + margin_);
      if (w1 > n_pushed()) break;
      process(buffer_.middleRows(w0 - start_, w1 - w0), w0, o0, o1);
      next_out_ = o1;
      // Keep the context the next block needs.
      const Eigen::Index keep_from = std::max<Eigen::Index>(start_, std::max<Eigen::Index>(0, o1 - margin_));
      const Eigen::Index drop = keep_from - start_;
      if (drop > 0) {
        const Eigen::Index kept = held_ - drop;
        for (Eigen::Index c = 0; c < buffer_.cols(); ++c) {
          double* column = buffer_.col(c).data();
          std::copy(column + drop, column + drop + kept, column);
        }
        held_ = kept;
        start_ = keep_from;
      }
    }
    if (m == 0 && taken < rows.rows()) {
      throw std::logic_error("overlap windows: buffer full without a complete window");
    }
    if (taken == rows.rows()) break;
  }
}

}  // namespace idbench
