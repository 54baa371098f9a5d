#include "idbench/workbench/formats/limits_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "engine/test_util.h"
#include "idbench/engine/puma560.h"

namespace idbench {
namespace {

using testing::ExpectInvalid;

// The PUMA's position limits stay; the file's velocity and acceleration
// limits replace the robot's.
TEST(LimitsFileTest, GivenValuesReplaceTheRobotsAndTheRestStay) {
  const RobotModel puma = MakePuma560();
  const std::vector<JointLimits> limits = ParseLimitsJson(
      R"({"joints": [{"qd_max": 1.5, "qdd_max": 4}, {}, {}, {}, {}, {"q_min": -1, "q_max": 2, "tau_max": 9}]})", puma,
      "l.json");
  ASSERT_EQ(limits.size(), 6u);
  EXPECT_EQ(limits[0].qd_max, 1.5);
  EXPECT_EQ(limits[0].qdd_max, 4.0);
  EXPECT_EQ(limits[0].q_min, puma.link(0).limits.q_min);
  EXPECT_EQ(limits[5].q_min, -1.0);
  EXPECT_EQ(limits[5].q_max, 2.0);
  EXPECT_EQ(limits[5].tau_max, 9.0);
}

// The motors' limits beside the joints': an omitted value is no limit; the
// joint limits read the same file unchanged; bad entries are named by field.
TEST(LimitsFileTest, ActuatorLimitsAreReadBesideTheJoints) {
  const RobotModel puma = MakePuma560();
  const std::string text =
      R"({"joints": [{}, {}, {}, {}, {}, {}], "actuators": [{"qd_max": 200}, {}, {"tau_max": 1.5}]})";
  EXPECT_EQ(ParseLimitsJson(text, puma, "l.json").size(), 6u);
  const std::vector<ActuatorLimit> motors = ParseActuatorLimitsJson(text, "l.json");
  ASSERT_EQ(motors.size(), 3u);  // the count is checked against the transmission (ActuatorLimits::Check)
  EXPECT_EQ(motors[0].qd_max, 200.0);
  EXPECT_FALSE(std::isfinite(motors[0].tau_max));
  EXPECT_FALSE(std::isfinite(motors[1].qd_max));
  EXPECT_EQ(motors[2].tau_max, 1.5);
  EXPECT_TRUE(ParseActuatorLimitsJson(R"({"joints": []})", "l.json").empty());
  EXPECT_EQ(ExpectInvalid([&] { ParseActuatorLimitsJson(R"({"joints": [], "actuators": [{"qd_max": 0}]})", "l.json"); }),
            "l.json: actuators[0].qd_max: must be > 0, got 0");
  EXPECT_EQ(ExpectInvalid([&] { ParseActuatorLimitsJson(R"({"joints": [], "actuators": [{"speed": 1}]})", "l.json"); }),
            "l.json: actuators[0].speed: unknown key (qd_max, tau_max)");
  EXPECT_EQ(ExpectInvalid([&] { ParseActuatorLimitsJson(R"({"joints": [], "actuators": {}})", "l.json"); }),
            "l.json: actuators: expected an array (one entry per motor)");
}

// Every broken file is one std::invalid_argument naming the file: a number
// out of range (1e999) escaped as nlohmann's out_of_range (found by
// tests/fuzz/limits_fuzzer), and keys are echoed escaped.
TEST(LimitsFileTest, BrokenFilesAreOneMessageNamingTheFile) {
  const RobotModel puma = MakePuma560();
  const auto refusal = [&](const std::string& text) {
    return ExpectInvalid([&] { ParseLimitsJson(text, puma, "l.json"); });
  };
  EXPECT_EQ(refusal(R"({"joints": [{"qd_max": 1e999}, {}, {}, {}, {}, {}]})").rfind("l.json: not valid JSON: ", 0), 0u);
  EXPECT_NE(refusal(R"({"joints": [{"qd_max": 1e999}, {}, {}, {}, {}, {}]})").find("number overflow"),
            std::string::npos);
  EXPECT_EQ(refusal(R"({"joints": [{"q\u0001": 1}, {}, {}, {}, {}, {}]})"),
            "l.json: joints[0].q\\x01: unknown key (q_min, q_max, qd_max, qdd_max, tau_max)");
  EXPECT_EQ(refusal(R"({"joints": [{}, {"qd_max": 0}, {}, {}, {}, {}]})"), "l.json: joints[1].qd_max: must be > 0, got 0");
  EXPECT_EQ(refusal(R"({"joints": []})"), "l.json: \"joints\" has 0 entries, robot 'puma560' has 6 joints");
  // Issue 35 item 9: qd_max 1 then 100 (1c4dd0f designed at 100 rad/s).
  EXPECT_EQ(refusal(R"({"joints": [{}, {"qd_max": 1, "qd_max": 100}, {}, {}, {}, {}]})"),
            "l.json: .joints[1].qd_max: key repeated in one object (each key may be given once)");
}

}  // namespace
}  // namespace idbench
