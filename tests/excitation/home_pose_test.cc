#include "idbench/excitation/home_pose.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "excitation/design_test_util.h"
#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

// tests/data/ur10e_like (make_robot.py): a UR10e-sized arm with mesh links,
// effort and velocity limits; at mid-range (q = 0) it is horizontal, the
// shoulder axis 0.16 m up and wrist 3 hanging 0.11 m below it with radius
// 0.035 m, so its lowest point is 0.015 m above the floor.
RobotModel UrLike() { return LoadUrdfFile(IDBENCH_SOURCE_DIR "/tests/data/ur10e_like/ur10e_like.urdf").model; }

std::vector<JointLimits> UrLimits(const RobotModel& model) {
  std::vector<JointLimits> limits;
  const double qdd[6] = {3, 3, 5, 5, 5, 5};  // the acceleration limits [rad/s²]
  for (int j = 0; j < model.n_dof(); ++j) {
    limits.push_back(model.link(j).limits);
    limits.back().qdd_max = qdd[j];
  }
  return limits;
}

// The static check at mid-range against the geometry above: wrist 3 to the
// ground 0.015 m less the 1 mm inflation of its mesh hull; no room to move.
TEST(HomePoseTest, MidRangeOfTheUrLikeArmIsJustAboveTheFloor) {
  const RobotModel model = UrLike();
  const std::vector<JointLimits> limits = UrLimits(model);
  const ClearanceModel clearance(model, 0.01);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(model.n_dof());
  const FeasibilityCheck check = CheckPose(model, limits, q, &clearance);
  EXPECT_TRUE(check.feasible()) << check.Explain();
  bool seen = false;
  for (const ConstraintMargin& m : check.margins) {
    if (m.pair != "wrist_3_link–ground") continue;
    seen = true;
    EXPECT_NEAR(m.value, 0.015 - 0.001, 1e-6);
  }
  EXPECT_TRUE(seen);
  EXPECT_LT(HomeRoom(model, limits, 0.02, q, &clearance), 0.0);
  // The search lifts the wrist off the floor.
  const HomePose home = FindHomePose(model, limits, 0.02, &clearance);
  EXPECT_EQ(home.source, "searched");
  EXPECT_GT(home.room, HomeRoom(model, limits, 0.02, q, &clearance));
  for (const ConstraintMargin& m : CheckPose(model, limits, home.q, &clearance).margins) {
    if (m.pair == "wrist_3_link–ground") {
      EXPECT_GT(m.value, 0.1);
    }
  }
}

// A pair is asked no room where no joint changes its distance (the UR-like
// shoulder link turns on its vertical axis above the floor), at most half
// what the joints can give it (the upper arm's shoulder end stays at
// 0.16 m − its radius, so never 10 cm beyond the clearance), and 10 cm where
// they can (the wrist swings up with the shoulder lift). So asked, the search
// finds a home with room.
TEST(HomePoseTest, PairsAreAskedTheRoomTheJointsCanGive) {
  const RobotModel model = UrLike();
  const std::vector<JointLimits> limits = UrLimits(model);
  const ClearanceModel clearance(model, 0.01);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(model.n_dof());
  const std::vector<double> asked = ClearanceRoomAsked(model, limits, q, &clearance);
  ASSERT_EQ(asked.size(), clearance.pairs().size());
  int seen = 0;
  for (const ConstraintMargin& m : CheckPose(model, limits, q, &clearance).margins) {
    if (m.quantity != "clearance") continue;
    const double a = asked[static_cast<size_t>(m.joint)];
    if (m.pair == "shoulder_link–ground") {
      EXPECT_EQ(a, 0.0);
      ++seen;
    } else if (m.pair == "upper_arm_link–ground") {
      EXPECT_GT(a, 0.0);
      EXPECT_LT(a, 0.1);
      ++seen;
    } else if (m.pair == "wrist_3_link–ground") {
      EXPECT_EQ(a, 0.1);
      ++seen;
    }
  }
  EXPECT_EQ(seen, 3);
  const HomePose home = FindHomePose(model, limits, 0.02, &clearance);
  EXPECT_TRUE(home.found) << home.room;
  EXPECT_EQ(home.room, HomeRoom(model, limits, 0.02, home.q, &clearance, &asked));
  EXPECT_GE(home.room, 0.0);
  EXPECT_TRUE(CheckPose(model, limits, home.q, &clearance).feasible());
}

// The case: the UR-like arm with the default 1 cm clearance, the
// defaults and acceleration limits 3/3/5/5/5/5 gets a design that improves
// on its start and is feasible at 1 kHz (one start of 100 evaluations here;
// the CLI's 4 × 300 reached cond 37.3 before the base link was an obstacle,
// BENCHMARKS.md; 45.6 now, docs/commands/design.md), with the CLI's default
// friction terms Fv, Fc, Ia. Before the home asked only the room the joints
// can give and starts kept off the clearance boundary, no start improved
// (cond 1405). (With Fv, Fc alone this seed's first start still does not
// move; starts 2-4 do: issue13b note.)
TEST(HomePoseTest, UrLikeDesignWithClearanceImproves) {
  const RobotModel model = UrLike();
  FrictionModel friction = testing::ViscousCoulomb();
  friction.rotor_inertia = true;
  const DesignRegressor regressor = DesignRegressor::JointTorque(model, friction);
  DesignOptions options;
  options.starts = 1;
  options.max_evaluations = 100;
  const DesignResult result = DesignExcitation(regressor, UrLimits(model), options);
  EXPECT_TRUE(result.check.feasible()) << result.check.Explain();
  // The start grows joint by joint after the common scale-down (cond ≈ 930
  // rather than ≈ 7000 before): the search still takes it down eightfold.
  // (Since the base link is an obstacle, issue 35 — the upper arm 3 mm above
  // it at q = 0 is held there — it reaches 116; 41 without it.)
  EXPECT_LT(result.final.cond, 0.15 * result.initial.cond);
  EXPECT_LT(result.final.cond, 150.0);
  EXPECT_EQ(result.starts[0].feasible_at, 0);
}

// A shoulder range that holds the upper arm in the floor (lift 0.3..0.5 rad
// tilts the 0.61 m upper arm down: its far end at 0.16 − 0.61 sin q < 0)
// admits no motion: said before any search, per constraint, with what to
// relax.
TEST(HomePoseTest, ShoulderRangeInTheFloorIsExplainedBeforeTheSearch) {
  const RobotModel model = UrLike();
  std::vector<JointLimits> limits = UrLimits(model);
  limits[1].q_min = 0.3, limits[1].q_max = 0.5;
  const FrictionModel friction = testing::ViscousCoulomb();
  const DesignRegressor regressor = DesignRegressor::JointTorque(model, friction);
  DesignOptions options;
  const DesignResult result = DesignExcitation(regressor, limits, options);
  ASSERT_EQ(result.status, DesignStatus::kNoMotionPossible);  // the ground, not an obstacle of a cell
  const DesignInfeasibility& e = result.infeasibility;
  EXPECT_TRUE(e.before_search);
  bool ground = false;
  for (const ConstraintMargin& m : e.check.margins) {
    if (m.margin < 0.0 && m.pair.find("–ground") != std::string::npos) ground = true;
  }
  EXPECT_TRUE(ground) << e.explanation;
  EXPECT_NE(e.explanation.find("below its minimum"), std::string::npos) << e.explanation;
  ASSERT_FALSE(e.advice.empty());
  EXPECT_EQ(e.advice[0].rfind("`clearance` (now 0.01 m)", 0), 0u) << e.explanation;
  // The shoulder's range holds the arm there: the advice names it too.
  bool shoulder_range = false;
  for (const std::string& a : e.advice) shoulder_range |= a.find("joint 2's range q_min..q_max (0.3..0.5 rad)") == 0;
  EXPECT_TRUE(shoulder_range) << e.explanation;
  EXPECT_EQ(result.evaluations, 0);  // nothing searched
}

// The PUMA with a TX40-like coupled wrist (N = [32, 32, 45, −48, 45, 32],
// motor 6 turning with joints 5 and 6), a motor torque limit on motor 2
// (τm2 = τ2/32, written out here rather than through A⁻ᵀ).
ActuatorLimits PumaMotors(int motor, double tau_max) {
  constexpr double kN[6] = {32, 32, 45, -48, 45, 32};
  ActuatorLimits actuators;
  actuators.transmission.actuator_from_joint = Eigen::MatrixXd::Zero(6, 6);
  for (int j = 0; j < 6; ++j) actuators.transmission.actuator_from_joint(j, j) = kN[j];
  actuators.transmission.actuator_from_joint(5, 4) = kN[5];
  actuators.motors.resize(6);
  actuators.motors[static_cast<size_t>(motor)].tau_max = tau_max;
  return actuators;
}
// Motor 2's gravity holding torque at q: |τ2|/32 from the inverse dynamics at rest.
double Motor2HoldingTorque(const RobotModel& model, const Eigen::VectorXd& q) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.n_dof());
  RobotData data(model);
  Eigen::VectorXd tau = InverseDynamics(model, q, zero, zero, &data);
  AddJointDynamicsTorque(model, zero, zero, &tau);
  return std::abs(tau[1]) / 32.0;
}

// A motor whose torque limit is half its gravity load at mid-range (the
// shoulder's range centred on 0.6 rad, where gravity loads it): the pose has
// room −1.02 (1 − margin − |τm|/τm_max = 1 − 0.02 − 2), and the search moves
// the home to where that motor holds the arm within 1 − margin of its limit;
// without the motors' limits mid-range has room.
TEST(HomePoseTest, TheHomeKeepsTheMotorsHoldingTorqueWithinItsLimit) {
  const RobotModel model = MakePuma560();
  std::vector<JointLimits> limits = testing::DesignLimits(model, 3.0, 20.0);
  limits[1].q_min = 0.6 - 1.5, limits[1].q_max = 0.6 + 1.5;
  Eigen::VectorXd middle(6);
  for (int j = 0; j < 6; ++j) middle[j] = 0.5 * (limits[static_cast<size_t>(j)].q_min + limits[static_cast<size_t>(j)].q_max);
  const double holding = Motor2HoldingTorque(model, middle);
  ASSERT_GT(holding, 0.1);
  const ActuatorLimits motors = PumaMotors(1, 0.5 * holding);
  EXPECT_EQ(FindHomePose(model, limits, 0.02, nullptr).source, "mid-range");
  EXPECT_NEAR(HomeRoom(model, limits, 0.02, middle, nullptr, nullptr, motors), 1.0 - 0.02 - 2.0, 1e-12);
  const HomePose home = FindHomePose(model, limits, 0.02, nullptr, motors);
  EXPECT_TRUE(home.found) << home.room;
  EXPECT_EQ(home.source, "searched");
  EXPECT_GE(home.room, 0.0);
  EXPECT_LE(Motor2HoldingTorque(model, home.q), (1.0 - 0.02) * 0.5 * holding);
  std::printf("motor 2 holding torque: %.4g N m at mid-range, limit %.4g, %.4g at the searched home\n", holding,
              0.5 * holding, Motor2HoldingTorque(model, home.q));
}

// A motor torque limit no home within the ranges can hold (the shoulder and
// elbow ranges narrowed to 0.2 rad around 0.6 and −0.4 rad, the limit a
// quarter of the least holding torque on a grid over them) is explained before the search, naming
// the motor, its joint, its |τm| at the home tried and the field to relax.
TEST(HomePoseTest, AMotorThatCannotHoldTheArmIsExplainedBeforeTheSearch) {
  const RobotModel model = MakePuma560();
  std::vector<JointLimits> limits = testing::DesignLimits(model, 3.0, 20.0);
  limits[1].q_min = 0.5, limits[1].q_max = 0.7;
  limits[2].q_min = -0.5, limits[2].q_max = -0.3;
  double least = INFINITY;
  Eigen::VectorXd q(6);
  for (int j = 0; j < 6; ++j) q[j] = 0.5 * (limits[static_cast<size_t>(j)].q_min + limits[static_cast<size_t>(j)].q_max);
  for (int a = 0; a <= 10; ++a) {
    for (int b = 0; b <= 10; ++b) {
      Eigen::VectorXd p = q;
      p[1] = limits[1].q_min + 0.02 * a;
      p[2] = limits[2].q_min + 0.02 * b;
      least = std::min(least, Motor2HoldingTorque(model, p));
    }
  }
  ASSERT_GT(least, 0.1);
  const double limit = 0.25 * least;
  DesignOptions options;
  options.actuators = PumaMotors(1, limit);
  const DesignRegressor regressor = DesignRegressor::JointTorque(model, testing::ViscousCoulomb());
  const DesignResult result = DesignExcitation(regressor, limits, options);
  ASSERT_EQ(result.status, DesignStatus::kNoMotionPossible);
  const DesignInfeasibility& e = result.infeasibility;
  EXPECT_TRUE(e.before_search);
  EXPECT_EQ(result.evaluations, 0);
  int violations = 0;
  for (const ConstraintMargin& m : e.check.margins) {
    if (m.margin >= 0.0) continue;
    ++violations;
    EXPECT_EQ(m.motor, 1);
    EXPECT_EQ(m.quantity, "tau");
    EXPECT_NEAR(m.value, Motor2HoldingTorque(model, result.home), 1e-9 * m.value);
    EXPECT_EQ(m.limit, limit);
  }
  EXPECT_EQ(violations, 1) << e.explanation;
  EXPECT_NE(e.explanation.find("no pose with room to move was found"), std::string::npos) << e.explanation;
  EXPECT_NE(e.explanation.find("motor 2 (joints joint2) tau: |τm| = "), std::string::npos) << e.explanation;
  bool relax = false;
  for (const std::string& a : e.advice) relax |= a.rfind("motor 2's torque limit actuators[1].tau_max", 0) == 0;
  EXPECT_TRUE(relax) << e.explanation;
}

}  // namespace
}  // namespace idbench
