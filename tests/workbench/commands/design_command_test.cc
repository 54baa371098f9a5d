// Actuator-space limits in the excitation design (issue 21): a 6-joint arm
// with a TX40-like coupled wrist (N = [32, 32, 45, −48, 45, 32], motor 6
// turns with joint 5: θ̇m6 = N6·(q̇5 + q̇6)), its joint limits loose, and a
// motor's velocity or torque limit that binds. An independent sampler reads
// trajectory.csv at 1 kHz and computes the motors' θ̇m and τm by hand (the
// TX40's relations written out, not Transmission): every motor stays within
// its limit, and the bound motor comes within a few % of it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/puma560.h"
#include "idbench/workbench/commands/design_command.h"
#include "workbench/commands/tx40_wrist.h"

namespace idbench {
namespace {

using testing::kTx40Ratio;

// Per row of trajectory.csv (t, q.*, qd.*, qdd.*): the peak |θ̇m| and |τm| of every motor.
struct MotorPeaks {
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(6), tau = Eigen::VectorXd::Zero(6);
  int rows = 0;
};
MotorPeaks SampleMotors(const RobotModel& model, const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  MotorPeaks peaks;
  RobotData data(model);
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
    EXPECT_EQ(v.size(), 19u) << line;
    if (v.size() != 19u) break;
    const Eigen::Map<const Eigen::VectorXd> q(v.data() + 1, 6), qd(v.data() + 7, 6), qdd(v.data() + 13, 6);
    Eigen::VectorXd tau = InverseDynamics(model, q, qd, qdd, &data);
    AddJointDynamicsTorque(model, qd, qdd, &tau);
    peaks.qd = peaks.qd.cwiseMax(testing::Tx40MotorRates(qd).cwiseAbs());
    peaks.tau = peaks.tau.cwiseMax(testing::Tx40MotorFromJointTorques(tau).cwiseAbs());
    ++peaks.rows;
  }
  return peaks;
}

class DesignActuatorLimitsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("idbench_design_actuators_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "tx40.json")
        << "{\"actuator_from_joint\": [[32,0,0,0,0,0], [0,32,0,0,0,0], [0,0,45,0,0,0], [0,0,0,-48,0,0], "
           "[0,0,0,0,45,0], [0,0,0,0,32,32]]}";
    options_.robot = "puma560";
    options_.design.harmonics = 3;
    options_.design.f0 = 0.2;
    options_.design.samples = 60;
    options_.design.starts = 2;
    options_.design.max_evaluations = 80;
    options_.design.clearance = -1.0;
    options_.quiet = true;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Joint limits loose (±2.5 rad, 3 rad/s, 20 rad/s²), and the motors' as given ("" for none).
  std::string WriteLimits(const std::string& actuators) const {
    std::string joints;
    for (int j = 0; j < 6; ++j) {
      joints += std::string(j ? ", " : "") + "{\"q_min\": -2.5, \"q_max\": 2.5, \"qd_max\": 3, \"qdd_max\": 20}";
    }
    const std::filesystem::path path = dir_ / "limits.json";
    std::ofstream(path) << "{\"joints\": [" << joints << "]" << (actuators.empty() ? "" : ", \"actuators\": " + actuators)
                        << "}";
    return path.string();
  }
  DesignCommandReport Run(const std::string& actuators) {
    options_.limits = WriteLimits(actuators);
    options_.transmission = actuators.empty() ? "" : (dir_ / "tx40.json").string();
    return RunDesign(model_, options_, nullptr);
  }

  std::filesystem::path dir_;
  RobotModel model_ = MakePuma560();
  DesignCommandOptions options_;
};

TEST_F(DesignActuatorLimitsTest, AMotorVelocityLimitBindsAndHolds) {
  // Without motor limits, the wrist motor reaches its peak; half of it binds.
  const DesignCommandReport free = Run("");
  ASSERT_TRUE(free.result.usable()) << free.result.Rejection();
  const MotorPeaks free_peaks = SampleMotors(model_, FormatDesignTrajectoryCsv(model_, options_, free));
  const double limit = 0.5 * free_peaks.qd[5];
  char motors[256];
  std::snprintf(motors, sizeof motors, "[{}, {}, {}, {}, {}, {\"qd_max\": %.17g}]", limit);
  const DesignCommandReport bound = Run(motors);
  ASSERT_TRUE(bound.result.usable()) << bound.result.Rejection() << "\n" << bound.result.check.Explain();
  const MotorPeaks peaks = SampleMotors(model_, FormatDesignTrajectoryCsv(model_, options_, bound));
  EXPECT_GT(peaks.rows, 1000);
  EXPECT_LE(peaks.qd[5], limit);
  EXPECT_GE(peaks.qd[5], 0.95 * limit) << "the motor's limit is not active";
  std::printf("motor 6: free peak %.4g rad/s, limit %.4g, designed peak %.4g (%.2f %%); cond %.4g free, %.4g bound\n",
              free_peaks.qd[5], limit, peaks.qd[5], 100.0 * peaks.qd[5] / limit, free.result.final.cond,
              bound.result.final.cond);
  // design.json: the actuator limits and their 1 kHz margins, the motor named.
  const nlohmann::json json = nlohmann::json::parse(FormatDesignJson(model_, options_, bound));
  ASSERT_EQ(json["actuators"].size(), 6u);
  EXPECT_DOUBLE_EQ(json["actuators"][5]["qd_max"].get<double>(), limit);
  EXPECT_EQ(json["actuators"][5]["joints"], "joint5, joint6");
  int motor_margins = 0;
  for (const nlohmann::json& m : json["check"]["margins"]) {
    if (!m.contains("motor")) continue;
    ++motor_margins;
    EXPECT_EQ(m["motor"], 6);
    EXPECT_EQ(m["quantity"], "qd");
    EXPECT_NEAR(m["value"].get<double>(), peaks.qd[5], 1e-9 * limit);
    EXPECT_GE(m["margin"].get<double>(), 0.0);
  }
  EXPECT_EQ(motor_margins, 1);
}

TEST_F(DesignActuatorLimitsTest, AMotorTorqueLimitBindsAndHolds) {
  // The coupled motor 5 (τm5 = (τ5 − τ6)/N5): 60 % of its free peak.
  const DesignCommandReport free = Run("");
  ASSERT_TRUE(free.result.usable()) << free.result.Rejection();
  const MotorPeaks free_peaks = SampleMotors(model_, FormatDesignTrajectoryCsv(model_, options_, free));
  const double limit = 0.6 * free_peaks.tau[4];
  char motors[256];
  std::snprintf(motors, sizeof motors, "[{}, {}, {}, {}, {\"tau_max\": %.17g}, {}]", limit);
  const DesignCommandReport bound = Run(motors);
  ASSERT_TRUE(bound.result.usable()) << bound.result.Rejection() << "\n" << bound.result.check.Explain();
  const MotorPeaks peaks = SampleMotors(model_, FormatDesignTrajectoryCsv(model_, options_, bound));
  EXPECT_LE(peaks.tau[4], limit);
  EXPECT_GE(peaks.tau[4], 0.9 * limit) << "the motor's limit is not active";
  std::printf("motor 5: free peak %.4g N m, limit %.4g, designed peak %.4g (%.2f %%); cond %.4g free, %.4g bound\n",
              free_peaks.tau[4], limit, peaks.tau[4], 100.0 * peaks.tau[4] / limit, free.result.final.cond,
              bound.result.final.cond);
}

TEST_F(DesignActuatorLimitsTest, ActuatorLimitsWithoutATransmissionAreRefused) {
  options_.limits = WriteLimits("[{}, {}, {}, {}, {}, {\"qd_max\": 10}]");
  try {
    RunDesign(model_, options_, nullptr);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("transmission: ", 0), 0u) << e.what();
  }
  // One entry per motor, each limit > 0: named by its field.
  options_.transmission = (dir_ / "tx40.json").string();
  options_.limits = WriteLimits("[{}, {}, {}, {}, {\"qd_max\": 10}]");
  EXPECT_THROW(
      try { RunDesign(model_, options_, nullptr); } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("actuators: expected 6 entries"), std::string::npos) << e.what();
        throw;
      },
      std::invalid_argument);
  options_.limits = WriteLimits("[{}, {}, {}, {}, {}, {\"qd_max\": -1}]");
  EXPECT_THROW(
      try { RunDesign(model_, options_, nullptr); } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("actuators[5].qd_max: must be > 0"), std::string::npos) << e.what();
        throw;
      },
      std::invalid_argument);
}

// A motion that breaks the wrist motor's limit is explained naming the motor
// and the joints it drives, as design prints it.
TEST_F(DesignActuatorLimitsTest, AViolationNamesTheMotor) {
  const DesignCommandReport free = Run("");
  ASSERT_TRUE(free.result.usable());
  const MotorPeaks free_peaks = SampleMotors(model_, FormatDesignTrajectoryCsv(model_, options_, free));
  ActuatorLimits actuators;
  actuators.transmission.actuator_from_joint = Eigen::MatrixXd::Zero(6, 6);
  for (int j = 0; j < 6; ++j) actuators.transmission.actuator_from_joint(j, j) = kTx40Ratio[j];
  actuators.transmission.actuator_from_joint(5, 4) = kTx40Ratio[5];
  actuators.motors.resize(6);
  actuators.motors[5].qd_max = 0.5 * free_peaks.qd[5];
  const FeasibilityCheck check = CheckTrajectoryLimits(model_, free.limits, free.result.RobotTrajectory(), 1000.0,
                                                       nullptr, actuators);
  EXPECT_FALSE(check.feasible());
  const std::string explained = check.Explain();
  EXPECT_EQ(explained.rfind("motor 6 (joints joint5, joint6) qd: |θ̇m| = ", 0), 0u) << explained;
  EXPECT_NE(explained.find("exceeds the limit"), std::string::npos) << explained;
}

// A motor torque limit below the home pose's gravity holding torque (through
// A⁻ᵀ) is explained before the search, as a joint's torque limit is: the
// motor, the joints it drives, its |τm| at home and the field to relax
// (actuators[1].tau_max). The holding torque is computed here by hand: the
// inverse dynamics at rest, then τm2 = τ2/N2 (MotorTorques).
TEST_F(DesignActuatorLimitsTest, AMotorTorqueLimitBelowTheHomeHoldingTorqueIsExplainedBeforeTheSearch) {
  const Eigen::VectorXd home = (Eigen::VectorXd(6) << 0.0, 0.6, -0.4, 0.0, 1.0, 0.0).finished();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  RobotData data(model_);
  Eigen::VectorXd tau = InverseDynamics(model_, home, zero, zero, &data);
  AddJointDynamicsTorque(model_, zero, zero, &tau);
  const double holding = std::abs(testing::Tx40MotorFromJointTorques(tau)[1]);
  ASSERT_GT(holding, 0.1) << "the shoulder's gravity load at this home";
  const double limit = 0.5 * holding;
  options_.home = {home.data(), home.data() + home.size()};
  char motors[256];
  std::snprintf(motors, sizeof motors, "[{}, {\"tau_max\": %.17g}, {}, {}, {}, {}]", limit);
  const DesignCommandReport report = Run(motors);
  const DesignResult& result = report.result;
  EXPECT_EQ(result.status, DesignStatus::kNoMotionPossible);
  EXPECT_TRUE(result.infeasibility.before_search);
  EXPECT_EQ(result.evaluations, 0);
  EXPECT_TRUE(result.starts.empty());
  // The one violation: motor 2's torque at the home pose, by the value computed here.
  int violations = 0;
  for (const ConstraintMargin& m : result.infeasibility.check.margins) {
    if (m.margin >= 0.0) continue;
    ++violations;
    EXPECT_EQ(m.motor, 1);
    EXPECT_EQ(m.quantity, "tau");
    EXPECT_EQ(m.driven, "joint2");
    EXPECT_NEAR(m.value, holding, 1e-9 * holding);
    EXPECT_EQ(m.limit, limit);
  }
  EXPECT_EQ(violations, 1);
  const std::string& explained = result.infeasibility.explanation;
  char line[256];
  std::snprintf(line, sizeof line, "motor 2 (joints joint2) tau: |τm| = %.6g N m at the home pose exceeds the limit %.6g N m",
                holding, limit);
  EXPECT_NE(explained.find(line), std::string::npos) << explained;
  EXPECT_NE(explained.find("actuators[1].tau_max"), std::string::npos) << explained;
}

}  // namespace
}  // namespace idbench
