#include "idbench/workbench/formats/trajectory_file.h"

#include <gtest/gtest.h>

#include "engine/test_util.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/constant_acceleration.h"
#include "idbench/excitation/fourier_series.h"
#include "idbench/excitation/ramped_trajectory.h"
#include "idbench/logs/joint_log_csv_reader.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

// 6 joints, 5 harmonics, coefficients with no short decimal form; amplitudes
// small enough to stay within the PUMA's joint limits.
FourierSeriesTrajectory MakeSeries(bool rest_to_rest, double duration = 10.0) {
  Eigen::MatrixXd a(6, 5), b(6, 5);
  for (int j = 0; j < 6; ++j) {
    for (int l = 0; l < 5; ++l) {
      a(j, l) = 0.3 * std::sin(1.0 + j * 5 + l) / (l + 1);
      b(j, l) = 0.3 * std::cos(2.0 + j * 7 + l) / (l + 1) / 3.0;
    }
  }
  Eigen::VectorXd q0(6);
  q0 << 0.1, std::numbers::pi / 7, -1.0 / 3, 0.2, -0.05, 1e-17;
  return FourierSeriesTrajectory(q0, a, b, 0.1, duration, rest_to_rest);
}

using testing::ExpectInvalid;

TEST(TrajectoryFileTest, FourierJsonRoundTripIsExact) {
  for (bool rest_to_rest : {false, true}) {
    const FourierSeriesTrajectory original = MakeSeries(rest_to_rest);
    const std::string text = FormatTrajectoryJson(original);
    EXPECT_EQ(text.rfind("{\n  \"family\": \"fourier\",", 0), 0u) << text;
    const std::unique_ptr<Trajectory> parsed = ParseTrajectoryJson(text, 6, "t.json");
    const auto* f = dynamic_cast<const FourierSeriesTrajectory*>(parsed.get());
    ASSERT_NE(f, nullptr);
    EXPECT_EQ(f->rest_to_rest(), rest_to_rest);
    EXPECT_EQ(f->f0(), original.f0());
    EXPECT_EQ(f->duration(), original.duration());
    EXPECT_EQ(f->q0(), original.q0());  // shortest round-trip decimals read back bit for bit
    EXPECT_EQ(f->a(), original.a());
    EXPECT_EQ(f->b(), original.b());
    for (double t = 0.0; t <= 10.0; t += 0.713) {
      const JointState x = f->At(t), y = original.At(t);
      EXPECT_LE((x.q - y.q).norm(), 1e-15 * y.q.norm());
      EXPECT_LE((x.qd - y.qd).norm(), 1e-15 * y.qd.norm());
      EXPECT_LE((x.qdd - y.qdd).norm(), 1e-15 * y.qdd.norm());
    }
    EXPECT_EQ(FormatTrajectoryJson(*f), text);
  }
}

TEST(TrajectoryFileTest, ConstantAccelerationJsonRoundTrip) {
  const ConstantAccelerationTrajectory original(Eigen::Vector2d(0.1, 1.0 / 3), Eigen::Vector2d(0, -0.7),
                                                Eigen::Vector2d(30 * std::numbers::pi / 180, 0), 2.0);
  const std::string text = FormatTrajectoryJson(original);
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["family"], "constant-acceleration");
  const auto parsed = ParseTrajectoryJson(text, 2, "c.json");
  const auto* c = dynamic_cast<const ConstantAccelerationTrajectory*>(parsed.get());
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->q0(), original.q0());
  EXPECT_EQ(c->qd0(), original.qd0());
  EXPECT_EQ(c->qdd(), original.qdd());
  EXPECT_EQ(c->duration(), 2.0);
}

TEST(TrajectoryFileTest, FamiliesWithoutCoefficientsAreRefused) {
  const SampledTrajectory sampled(Eigen::Vector2d(0, 1), Eigen::MatrixXd::Zero(1, 2));
  EXPECT_NE(ExpectInvalid([&] { FormatTrajectoryJson(sampled); }).find("write it as CSV"), std::string::npos);
  const auto reversed = MakeBuiltinMotion("general-reversed", 6, 4.0, 0.5);
  EXPECT_THROW(FormatTrajectoryJson(*reversed), std::invalid_argument);
}

// Every bad file gives one message naming the file, the key and what is wrong.
TEST(TrajectoryFileTest, BadJsonNamesTheKey) {
  using nlohmann::json;
  const json good = json::parse(FormatTrajectoryJson(MakeSeries(false)));
  auto edit = [&](const std::function<void(json&)>& change) {
    json j = good;
    change(j);
    return j.dump();
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{\"family\": \"fourier\",", "bad.json: not valid JSON: "},
      {"[1, 2]", "bad.json: expected a JSON object, got array"},
      {edit([](json& j) { j.erase("family"); }), "bad.json: key 'family': missing"},
      {edit([](json& j) { j["family"] = "spline"; }),
       "bad.json: key 'family': expected \"fourier\" or \"constant-acceleration\", got \"spline\""},
      {edit([](json& j) { j.erase("f0"); }), "bad.json: key 'f0': missing"},
      {edit([](json& j) { j["f0"] = 0.0; }), "bad.json: key 'f0': must be > 0, got 0.0"},
      {edit([](json& j) { j["f0"] = "fast"; }), "bad.json: key 'f0': expected a number, got \"fast\""},
      {edit([](json& j) { j["duration"] = -1; }), "bad.json: key 'duration': must be > 0, got -1"},
      {edit([](json& j) { j["rest_to_rest"] = 1; }),
       "bad.json: key 'rest_to_rest': expected true or false, got 1"},
      {edit([](json& j) { j["q0"].erase(5); }),
       "bad.json: key 'q0': expected an array of 6 numbers (one per joint of the robot), got 5 entries"},
      {edit([](json& j) { j["q0"][1] = "x"; }), "bad.json: key 'q0': entry 2: expected a number, got \"x\""},
      {edit([](json& j) { j["a"].erase(0); }),
       "bad.json: key 'a': expected 6 rows (one per joint of the robot), got 5"},
      {edit([](json& j) { j["a"][0] = json::array(); }),
       "bad.json: key 'a': row 1: expected an array of at least one coefficient, got []"},
      {edit([](json& j) { j["b"][2].erase(4); }),
       "bad.json: key 'b': row 3: expected 5 numbers (one per harmonic), got 4"},
      {edit([](json& j) { j["b"][3][1] = nullptr; }),
       "bad.json: key 'b': row 4: entry 2: expected a number, got null"},
      {edit([](json& j) { j["durration"] = 3; }),
       "bad.json: key 'durration': unknown for this family; expected a, b, duration, f0, family, q0, rest_to_rest"},
      {R"({"family": "constant-acceleration", "duration": 1, "q0": [0,0,0,0,0,0], "qd0": [0,0,0,0,0,0]})",
       "bad.json: key 'qdd': missing"},
  };
  for (const auto& [text, message] : cases) {
    const std::string what = ExpectInvalid([&] { ParseTrajectoryJson(text, 6, "bad.json"); });
    EXPECT_EQ(what.substr(0, message.size()), message) << text;
  }
  // Without rest_to_rest the plain series is meant.
  const auto plain = ParseTrajectoryJson(edit([](json& j) { j.erase("rest_to_rest"); }), 6, "ok.json");
  EXPECT_FALSE(dynamic_cast<const FourierSeriesTrajectory&>(*plain).rest_to_rest());
}

// The controller-rate CSV read back: exactly the samples, and in between the
// quintic Hermite interpolation (error bound as in sampled_trajectory_test.cc:
// h⁶/46080·|q⁽⁶⁾| with h = 0.01 s, |q⁽⁶⁾| ≲ 1, so q to 1e-15 plus rounding).
TEST(TrajectoryFileTest, CsvRoundTripFollowsTheOriginal) {
  const RobotModel puma = MakePuma560();
  const FourierSeriesTrajectory original = MakeSeries(true, 2.345);
  const std::string text = FormatTrajectoryCsv(original, 100.0);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "t,q1,q2,q3,q4,q5,q6,qd1,qd2,qd3,qd4,qd5,qd6,qdd1,qdd2,qdd3,qdd4,qdd5,qdd6");
  const SampledTrajectory sampled = ParseTrajectoryCsv(text, puma, "traj.csv");
  ASSERT_EQ(sampled.n_samples(), 235);  // k/100 for k = 0..⌊234.5⌋
  EXPECT_EQ(sampled.duration(), 2.34);
  for (int k = 0; k < sampled.n_samples(); k += 13) {
    const JointState x = sampled.At(sampled.t()[k]), y = original.At(k / 100.0);
    EXPECT_EQ(x.q, y.q);
    EXPECT_EQ(x.qd, y.qd);
    EXPECT_EQ(x.qdd, y.qdd);
  }
  for (double t = 0.0; t <= sampled.duration(); t += 0.0371) {
    const JointState x = sampled.At(t), y = original.At(t);
    EXPECT_LT((x.q - y.q).cwiseAbs().maxCoeff(), 1e-13) << t;
    EXPECT_LT((x.qd - y.qd).cwiseAbs().maxCoeff(), 1e-11) << t;
    EXPECT_LT((x.qdd - y.qdd).cwiseAbs().maxCoeff(), 1e-9) << t;
  }
  // A duration that is a whole number of samples keeps its last one.
  const ConstantAccelerationTrajectory short_motion(Eigen::VectorXd::Zero(6), Eigen::VectorXd::Zero(6),
                                                    Eigen::VectorXd::Constant(6, 0.1), 0.3);
  EXPECT_EQ(ParseTrajectoryCsv(FormatTrajectoryCsv(short_motion, 10.0), puma, "c.csv").n_samples(), 4);
  EXPECT_THROW(FormatTrajectoryCsv(short_motion, 0.0), std::invalid_argument);
}

// What `design` writes: a motion framed by ramps from and to a home pose,
// headed with the joint names, with or without qd and qdd. Read back, the
// samples are exactly the trajectory evaluated (shortest round-trip numbers;
// the interpolation passes through its knots).
TEST(TrajectoryFileTest, CsvWithJointNamesReadsBackTheRampedMotion) {
  const RobotModel puma = MakePuma560();
  std::vector<std::string> names;
  for (const Link& link : puma.links()) names.push_back(link.joint_name);
  const Eigen::VectorXd home = Eigen::VectorXd::LinSpaced(6, -0.3, 0.2);
  const RampedTrajectory robot(std::make_shared<FourierSeriesTrajectory>(MakeSeries(false, 2.0)), home, 0.5);
  for (const bool derivatives : {true, false}) {
    const std::string text = FormatTrajectoryCsv(robot, 250.0, derivatives, names);
    std::string header = "t";
    for (const char* prefix : {"q", "qd", "qdd"}) {
      for (const std::string& name : names) {
        if (derivatives || prefix == std::string("q")) header += "," + std::string(prefix) + "." + name;
      }
    }
    EXPECT_EQ(text.substr(0, text.find('\n')), header);
    const SampledTrajectory sampled = ParseTrajectoryCsv(text, puma, "traj.csv");
    ASSERT_EQ(sampled.n_samples(), 751);  // 3 s at 250 Hz, both ends
    for (int k = 0; k < sampled.n_samples(); k += 7) {
      const JointState x = sampled.At(sampled.t()[k]), y = robot.At(k / 250.0);
      EXPECT_EQ(x.q, y.q) << k;
      if (derivatives) {
        EXPECT_EQ(x.qd, y.qd) << k;
      }
    }
    EXPECT_EQ(sampled.At(0.0).q, home);  // starts and ends at home
    EXPECT_EQ(sampled.At(3.0).q, home);
  }
  // Columns are matched by name, in any order; an unknown name is refused.
  const std::string swapped = "t,q." + names[1] + ",q." + names[0] + ",q3,q4,q5,q6\n0,0.25,0.5,0,0,0,0\n1,0.25,0.5,0,0,0,0\n";
  EXPECT_EQ(ParseTrajectoryCsv(swapped, puma, "s.csv").At(0.5).q.head(2), Eigen::Vector2d(0.5, 0.25));
  EXPECT_EQ(ExpectInvalid([&] { ParseTrajectoryCsv("\nt,q.elbow,q2\n", puma, "u.csv"); }),
            "u.csv:2: column 2 ('q.elbow'): no joint 'elbow' in " + puma.name());
  EXPECT_THROW(FormatTrajectoryCsv(robot, 250.0, true, {"a", "b"}), std::invalid_argument);
  names[2] = "a,b";
  EXPECT_THROW(FormatTrajectoryCsv(robot, 250.0, true, names), std::invalid_argument);
}

TEST(TrajectoryFileTest, CsvWithPositionsAloneOrWithTorques) {
  const RobotModel puma = MakePuma560();
  // q alone: the natural cubic spline through the positions.
  const std::string q_only = "t,q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0,0\n1,0.5,0,0,0,0,0\n2,1,0,0,0,0,0\n";
  const SampledTrajectory line = ParseTrajectoryCsv(q_only, puma, "q.csv");
  EXPECT_DOUBLE_EQ(line.At(1.5).q[0], 0.75);  // a straight line stays straight
  EXPECT_DOUBLE_EQ(line.At(0.3).qd[0], 0.5);
  // A joint log (with torques) is also a trajectory.
  const std::string log = "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n0,0,0,0,0,0,0,1,1,1,1,1,1\n"
                          "1,0.5,0,0,0,0,0,1,1,1,1,1,1\n";
  EXPECT_EQ(ParseTrajectoryCsv(log, puma, "log.csv").n_samples(), 2);
  // The joint-log parser still wants torques for identification.
  EXPECT_EQ(ExpectInvalid([&] { ParseJointLogCsv(q_only, puma, "q.csv"); }),
            "q.csv:1: missing column 'tau1' (robot has 6 joints)");
}

TEST(TrajectoryFileTest, BadCsvGivesTheJointLogMessages) {
  const RobotModel puma = MakePuma560();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"t,q1,q2,q3,q4,q5\n0,0,0,0,0,0\n", "bad.csv:1: missing column 'q6' (robot has 6 joints)"},
      {"t,q1,q2,q3,q4,q5,q6,tau2\n0,0,0,0,0,0,0,1\n1,0,0,0,0,0,0,1\n",
       "bad.csv:1: column 'tau2' without tau1: give all of tau1..tau6 or none"},
      {"t,q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0,0\n1,9,0,0,0,0,0\n", "bad.csv:3: column 2 ('q1'): 9 rad is outside joint 1's limits"},
      {"t,q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0,0\n0,0,0,0,0,0,0\n", "bad.csv:3: column 1 ('t'): time 0.000000 does not increase"},
      {"t,q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0,0\n", "bad.csv: 1 sample, expected at least 2 to interpolate"},
  };
  for (const auto& [text, message] : cases) {
    const std::string what = ExpectInvalid([&] { ParseTrajectoryCsv(text, puma, "bad.csv"); });
    EXPECT_EQ(what.substr(0, message.size()), message) << text;
  }
}

TEST(TrajectoryFileTest, TrajectoryArgIsABuiltinNameOrAFile) {
  const RobotModel puma = MakePuma560();
  const BuiltinMotionOptions builtin{.duration = 4.0, .paper_qdd = 0.5};
  const auto general = LoadTrajectoryArg("general", puma, builtin);
  EXPECT_EQ(general->duration(), 4.0);
  EXPECT_EQ(general->At(1.3).q, MakeGeneralMotion(6, 4.0)->At(1.3).q);

  const fs::path dir = fs::temp_directory_path() / "idbench_trajectory_file_test";
  fs::create_directories(dir);
  const FourierSeriesTrajectory series = MakeSeries(true, 7.5);
  std::ofstream(dir / "t.json") << FormatTrajectoryJson(series);
  std::ofstream(dir / "t.csv") << FormatTrajectoryCsv(series, 200.0);
  const auto from_json = LoadTrajectoryArg((dir / "t.json").string(), puma, builtin);
  const auto from_csv = LoadTrajectoryArg((dir / "t.csv").string(), puma, builtin);
  EXPECT_EQ(from_json->duration(), 7.5);  // the file's own duration
  EXPECT_EQ(from_csv->duration(), 7.5);
  EXPECT_EQ(from_json->At(2.0).q, series.At(2.0).q);
  EXPECT_LT((from_csv->At(2.0025).q - series.At(2.0025).q).norm(), 1e-13);

  const std::string missing = (dir / "missing.json").string();
  EXPECT_EQ(ExpectInvalid([&] { LoadTrajectoryArg(missing, puma, builtin); }), missing + ": cannot read the file (No such file or directory)");
  EXPECT_EQ(ExpectInvalid([&] { LoadTrajectoryArg(dir.string() + "/.csv", puma, builtin); }),
            dir.string() + "/.csv: cannot read the file (No such file or directory)");
  for (const std::string bad : {"sideways", "motion.txt"}) {
    EXPECT_EQ(ExpectInvalid([&] { LoadTrajectoryArg(bad, puma, builtin); }),
              "trajectory '" + bad + "': not a built-in motion (paper, general, general-reversed) nor a file "
              "ending in .json or .csv");
  }
  fs::remove_all(dir);
}

// Numbers out of range (nlohmann's out_of_range escaped as another exception),
// more harmonics than design uses, and a motion no double can hold (f0 =
// 1e-300 gave q ≈ -1.6e297 rad) are one std::invalid_argument naming the file.
TEST(TrajectoryFileTest, OutOfRangeNumbersManyHarmonicsAndUnusableMotionsAreRefused) {
  const RobotModel puma = MakePuma560();
  const auto fourier = [](const std::string& f0, int harmonics) {
    std::string row = "[";
    for (int k = 0; k < harmonics; ++k) row += (k ? ",0.01" : "0.01");
    row += "]";
    std::string rows = "[";
    for (int j = 0; j < 6; ++j) rows += (j ? "," : "") + row;
    return R"({"family": "fourier", "f0": )" + f0 + R"(, "duration": 1, "q0": [0,0,0,0,0,0], "a": )" + rows +
           R"(], "b": )" + rows + "]}";
  };
  EXPECT_EQ(ExpectInvalid([&] { ParseTrajectoryJson(fourier("1e999", 2), 6, "t.json"); })
                .rfind("t.json: not valid JSON: ", 0),
            0u);
  EXPECT_EQ(ExpectInvalid([&] { ParseTrajectoryJson(fourier("0.1", 51), 6, "t.json"); }),
            "t.json: key 'a': 51 harmonics, at most 50 (as idbench design)");
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "idbench_tiny_f0.json";
  std::ofstream(path) << fourier("1e-300", 2);
  const std::string message =
      ExpectInvalid([&] { LoadTrajectoryArg(path.string(), puma, BuiltinMotionOptions{}); });
  // q(0) = q0 − Σ_l b_l/(ω l) = −(0.01 + 0.01/2)/(2π·1e-300) = −2.3873241463784...e297 rad.
  EXPECT_EQ(message.rfind(path.string() + ": at t = 0 s joint 1 has q = -2.38732414637843", 0), 0u) << message;
  EXPECT_NE(message.find("e+297 rad"), std::string::npos) << message;
  std::filesystem::remove(path);
}

// Issue 35 items 3 and 9: 100 000 nested arrays (200 KB; on 1c4dd0f the
// message showing the value overflowed the stack) and a repeated key (the
// last one silently won) are refused, each naming the key path.
TEST(TrajectoryFileTest, DeepNestingAndRepeatedKeysAreRefused) {
  const std::string deep = "{\"family\": " + std::string(100'000, '[') + std::string(100'000, ']') + "}";
  const std::string what = ExpectInvalid([&] { ParseTrajectoryJson(deep, 6, "t.json"); });
  EXPECT_EQ(what.rfind("t.json: .family[0][0]", 0), 0u) << what;
  EXPECT_NE(what.find(": more than 64 nested arrays and objects"), std::string::npos) << what;
  EXPECT_EQ(ExpectInvalid([&] {
              ParseTrajectoryJson(R"({"family": "constant-acceleration", "duration": 1, "duration": 100})", 6, "t.json");
            }),
            "t.json: .duration: key repeated in one object (each key may be given once)");
}

}  // namespace
}  // namespace idbench
