#include "angle_unit_check.h"

#include <numbers>

#include "number_format.h"

namespace idbench::internal {

constexpr double kSmallMotionDeg = 5.0;
void WarnIfRadiansReadAsDegrees(const JointLogFormat& format, const std::string& source, const Eigen::MatrixXd& q,
                                std::vector<std::string>* warnings) {
  if (!format.degrees() || q.rows() < 2) return;
  WarnIfRadiansReadAsDegrees(format, source, q.colwise().minCoeff().transpose(), q.colwise().maxCoeff().transpose(),
                             q.rows(), warnings);
}

void WarnIfRadiansReadAsDegrees(const JointLogFormat& format, const std::string& source, const Eigen::VectorXd& q_min,
                                const Eigen::VectorXd& q_max, std::int64_t n_samples, std::vector<std::string>* warnings) {
  if (!format.degrees() || n_samples < 2) return;
  const double span_deg = (q_max - q_min).maxCoeff() * 180.0 / std::numbers::pi;
  if (span_deg < kSmallMotionDeg) {
    warnings->push_back(source + ": with angle_unit deg no joint moves more than " + Shortest(span_deg) +
                        "° over the log (less than " + Shortest(kSmallMotionDeg) +
                        "°): is the log in radians? Read in degrees, a motion of 2 rad becomes 2°, and the fit "
                        "is then badly conditioned");
  }
}

}  // namespace idbench::internal
