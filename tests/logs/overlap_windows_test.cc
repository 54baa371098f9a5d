#include "idbench/logs/overlap_windows.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace idbench {
namespace {

// Every output block is handed on once, in order, with the rows of its
// window exactly those of the signal, whatever the push sizes.
TEST(OverlapWindowsTest, WindowsHoldTheSignalAroundEachBlock) {
  const Eigen::Index n = 1001;
  Eigen::MatrixXd signal(n, 2);
  for (Eigen::Index s = 0; s < n; ++s) signal.row(s) << s, -2.0 * s;
  for (Eigen::Index margin : {0, 3, 50, 400}) {
    for (Eigen::Index block : {1, 7, 100, 2000}) {
      for (Eigen::Index push : {1, 13, 1000, 1001}) {
        OverlapWindows windows(n, 2, margin, block);
        Eigen::Index next = 0;
        auto process = [&](Eigen::Ref<const Eigen::MatrixXd> window, Eigen::Index w0, Eigen::Index o0,
                           Eigen::Index o1) {
          EXPECT_EQ(o0, next);
          EXPECT_EQ(o1, std::min(n, o0 + block));
          EXPECT_EQ(w0, std::max<Eigen::Index>(0, o0 - margin));
          EXPECT_EQ(w0 + window.rows(), std::min(n, o1 + margin));
          EXPECT_EQ(window, signal.middleRows(w0, window.rows()));
          next = o1;
        };
        for (Eigen::Index s = 0; s < n; s += push) windows.Push(signal.middleRows(s, std::min(push, n - s)), process);
        EXPECT_TRUE(windows.done());
        EXPECT_EQ(next, n) << "margin " << margin << ", block " << block << ", push " << push;
      }
    }
  }
}

TEST(OverlapWindowsTest, RejectsTooManyRowsAndWrongColumns) {
  OverlapWindows windows(10, 2, 2, 4);
  auto ignore = [](Eigen::Ref<const Eigen::MatrixXd>, Eigen::Index, Eigen::Index, Eigen::Index) {};
  EXPECT_THROW(windows.Push(Eigen::MatrixXd::Zero(11, 2), ignore), std::invalid_argument);
  EXPECT_THROW(windows.Push(Eigen::MatrixXd::Zero(3, 3), ignore), std::invalid_argument);
  EXPECT_THROW(OverlapWindows(0, 1, 1, 1), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
