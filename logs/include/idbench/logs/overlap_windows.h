// A signal of known length handed over in consecutive blocks of rows (a
// streamed log), handed on as overlapping windows: each block of output rows
// with `margin` rows of context on both sides (fewer at the signal's ends),
// what a zero-phase filter or a central difference needs to give inside the
// block what it gives on the whole signal. Holds at most block + 2·margin rows
// plus what one Push appends.
#pragma once

#include <functional>

#include <Eigen/Core>

namespace idbench {

class OverlapWindows {
 public:
  // window: rows [w0, w0 + window.rows()) of the signal; the caller's output
  // is rows [o0, o1), w0 = max(0, o0 − margin), w0 + window.rows() =
  // min(n_total, o1 + margin).
  using Process = std::function<void(Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0,
                                     Eigen::Index o1)>;

  // n_total rows of n_cols columns will be pushed. Throws
  // std::invalid_argument unless n_total >= 1, margin >= 0, block >= 1.
  OverlapWindows(Eigen::Index n_total, Eigen::Index n_cols, Eigen::Index margin, Eigen::Index block);

  // Appends the next rows (n_cols columns; at most the rows still to come)
  // and calls `process` for every output block whose window is now complete,
  // in order. Throws std::invalid_argument on a column count mismatch or too
  // many rows.
  void Push(Eigen::Ref<const Eigen::MatrixXd> rows, const Process& process);

  Eigen::Index n_pushed() const { return start_ + held_; }
  bool done() const { return next_out_ == n_total_; }

 private:
  Eigen::Index n_total_, margin_, block_;
  Eigen::MatrixXd buffer_;  // rows [start_, start_ + held_) of the signal in its first held_ rows
  Eigen::Index start_ = 0, held_ = 0;
  Eigen::Index next_out_ = 0;  // first output row not yet handed on
};

}  // namespace idbench
