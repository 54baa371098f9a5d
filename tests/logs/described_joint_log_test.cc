#include "idbench/logs/joint_log_description.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "engine/test_util.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/urdf.h"
#include "idbench/logs/joint_log_csv_reader.h"
#include "idbench/logs/open_joint_log.h"
#include "idbench/logs/recorded_joint_log_source.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::ExpectInvalid;

// A 7-joint chain (the Panda's joint count), each joint about z, limits ±2.8.
RobotModel SevenJoints() {
  std::string xml = "<robot name='seven'><link name='l0'/>";
  for (int j = 1; j <= 7; ++j) {
    xml += "<link name='l" + std::to_string(j) + "'><inertial><mass value='1'/><origin xyz='0 0 0.05'/>"
           "<inertia ixx='0.01' iyy='0.01' izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial></link>"
           "<joint name='j" + std::to_string(j) + "' type='revolute'><parent link='l" + std::to_string(j - 1) +
           "'/><child link='l" + std::to_string(j) + "'/><origin xyz='0 0 0.1' rpy='" + (j % 2 ? "1.5707963 0 0" : "0 0 0") +
           "'/><axis xyz='0 0 1'/><limit lower='-2.8' upper='2.8' effort='100' velocity='2'/></joint>";
  }
  return LoadUrdfString(xml + "</robot>", "seven.urdf").model;
}

// The truth: sample k of joint j (0-based) for each signal, exact in binary
// after "%.17g" (the independent writer below) and from_chars.
double Q(int k, int j) { return 0.5 * std::sin(0.01 * k + j); }
double Qd(int k, int j) { return 0.3 * std::cos(0.02 * k - j); }
double Tau(int k, int j) { return 10.0 * j - 0.125 * k; }

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", v);
  return text;
}

// `line` n times, each ended by '\n'.
std::string Lines(const std::string& line, int n) {
  std::string out;
  for (int k = 0; k < n; ++k) out += line + "\n";
  return out;
}

class DescribedJointLogTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("described_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // One number per line, `per_sample` values per sample of n samples.
  fs::path WriteOnePerLine(const std::string& name, int n, int per_sample, double (*f)(int, int)) {
    std::string text;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < per_sample; ++j) text += Number(f(k, j)) + "\n";
    return Write(name, text);
  }
  fs::path dir_;
};

// Motor-side columns through a coupled transmission (the TX40's wrist:
// θm6 = N6·(q5 + q6), offsets on joints 2 and 3), currents times drive gains:
// read back as the joint-side truth. The writer applies A and A⁻ᵀ by hand.
TEST_F(DescribedJointLogTest, MotorSideColumnsAreMappedThroughTheTransmission) {
  const RobotModel puma = MakePuma560();
  const double N[6] = {32, 32, 45, -48, 45, 32}, K[6] = {0.5, 0.5, 0.4, 0.3, 0.3, 0.2};
  const double q0[6] = {0, -1.5707963267948966, 1.5707963267948966, 0, 0, 0};
  constexpr int n = 50;
  std::string csv = "t,qm1,qm2,qm3,qm4,qm5,qm6,qdm1,qdm2,qdm3,qdm4,qdm5,qdm6,im1,im2,im3,im4,im5,im6\n";
  for (int k = 0; k < n; ++k) {
    double qm[6], qdm[6], im[6];
    for (int j = 0; j < 6; ++j) {
      qm[j] = N[j] * (Q(k, j) - q0[j]);
      qdm[j] = N[j] * Qd(k, j);
      im[j] = Tau(k, j) / N[j] / K[j];
    }
    qm[5] = N[5] * (Q(k, 4) + Q(k, 5));
    qdm[5] = N[5] * (Qd(k, 4) + Qd(k, 5));
    im[4] = (Tau(k, 4) - Tau(k, 5)) / N[4] / K[4];  // τ5 = N5·τm5 + N6·τm6
    csv += Number(0.01 * k);
    for (const double* v : {qm, qdm, im}) {
      for (int j = 0; j < 6; ++j) csv += "," + Number(v[j]);
    }
    csv += "\n";
  }
  Write("motor.csv", csv);
  const fs::path desc = Write("motor.yaml", R"(files: [{path: motor.csv}]
drive_gains: [0.5, 0.5, 0.4, 0.3, 0.3, 0.2]
transmission:
  actuator_from_joint: [[32, 0, 0, 0, 0, 0], [0, 32, 0, 0, 0, 0], [0, 0, 45, 0, 0, 0],
                        [0, 0, 0, -48, 0, 0], [0, 0, 0, 0, 45, 0], [0, 0, 0, 0, 32, 32]]
  joint_offset: [0, -1.5707963267948966, 1.5707963267948966, 0, 0, 0]
)");
  const auto source = OpenJointLog(desc.string(), puma, {}, TorqueColumns::kRequired);
  ASSERT_TRUE(source->layout().transmission.has_value());
  const RecordedJointLog log = ReadWholeLog(*source, 7);
  ASSERT_EQ(log.log.n_samples(), n);
  double q_error = 0.0, qd_error = 0.0, tau_error = 0.0;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < 6; ++j) {
      q_error = std::max(q_error, std::abs(log.log.q(k, j) - Q(k, j)));
      qd_error = std::max(qd_error, std::abs(log.log.qd(k, j) - Qd(k, j)));
      tau_error = std::max(tau_error, std::abs(log.log.tau(k, j) - Tau(k, j)) / 60.0);
    }
  }
  EXPECT_LT(q_error, 1e-14);
  EXPECT_LT(qd_error, 1e-14);
  EXPECT_LT(tau_error, 1e-14);
  bool noted = false;
  for (const std::string& note : source->layout().notes) noted = noted || note.find("qm*, qdm*, im* read on the actuator side") != std::string::npos;
  EXPECT_TRUE(noted);

  // A joint outside its limits after the mapping names the file, line and joint.
  // (θm2, θm3 put joints 2 and 3 at 0.)
  Write("motor.csv", "t,qm1,qm2,qm3,qm4,qm5,qm6,im1,im2,im3,im4,im5,im6\n0,0,50.26548245743669,-70.68583470577035,0,0,0,"
                     "1,1,1,1,1,1\n0.01,0,50.26548245743669,-70.68583470577035,0,0,640,1,1,1,1,1,1\n");
  const std::string what = ExpectInvalid([&] { ReadWholeLog(*OpenJointLog(desc.string(), puma, {}, TorqueColumns::kRequired), 7); });
  EXPECT_EQ(what.rfind((dir_ / "motor.csv").string() + ":3: joint 6 at 20 rad from the motor positions", 0), 0u) << what;
}

// The Panda set of Gaz et al.: time, positions, velocities, torques, one
// number per line, 7 lines per sample (time 1); read back exactly.
TEST_F(DescribedJointLogTest, PandaShapedOneValuePerLineFilesReadBackExactly) {
  const RobotModel seven = SevenJoints();
  constexpr int n = 300;
  WriteOnePerLine("time.txt", n, 1, [](int k, int) { return 0.001 * k + 0.5; });
  WriteOnePerLine("positions.txt", n, 7, Q);
  WriteOnePerLine("velocities.txt", n, 7, Qd);
  WriteOnePerLine("torques.txt", n, 7, Tau);
  const fs::path desc = Write("panda.json", R"({"files": [
      {"path": "time.txt", "layout": "one-value-per-line", "stride": 1, "columns": "t"},
      {"path": "positions.txt", "layout": "one-value-per-line", "stride": 7, "columns": "q1..q7"},
      {"path": "velocities.txt", "layout": "one-value-per-line", "stride": 7, "columns": ["qd1..qd7"]},
      {"path": "torques.txt", "layout": "one-value-per-line", "stride": 7, "columns": "tau1..tau7"}]})");
  for (const Eigen::Index chunk : {Eigen::Index{1}, Eigen::Index{7}, Eigen::Index{65536}}) {
    const auto source = OpenJointLog(desc.string(), seven, {}, TorqueColumns::kRequired);
    EXPECT_FALSE(source->layout().has_qdd);
    const RecordedJointLog r = ReadWholeLog(*source, chunk);
    ASSERT_EQ(r.log.n_samples(), n);
    for (int k = 0; k < n; ++k) {
      ASSERT_EQ(r.log.t[k], 0.001 * k + 0.5);
      for (int j = 0; j < 7; ++j) {
        ASSERT_EQ(r.log.q(k, j), Q(k, j));
        ASSERT_EQ(r.log.qd(k, j), Qd(k, j));
        ASSERT_EQ(r.log.tau(k, j), Tau(k, j));
      }
    }
    EXPECT_EQ(r.lines[2], 3);  // the time file's line of sample 2
  }
}

// The Stäubli TX40 set of FIGAROH: two CSV files with a vendor header
// (Joint_1..Joint_6), no time column, a rate; in YAML, degrees and gains.
TEST_F(DescribedJointLogTest, Tx40ShapedTwoFilesWithARateReadBackExactly) {
  const RobotModel puma = MakePuma560();
  constexpr int n = 500;
  std::string pos = "Joint_1,Joint_2,Joint_3,Joint_4,Joint_5,Joint_6\n", cur = pos;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < 6; ++j) {
      pos += Number(Q(k, j) * 180.0 / M_PI) + (j < 5 ? "," : "\n");
      cur += Number(Tau(k, j)) + (j < 5 ? "," : "\n");
    }
  }
  Write("pos_read_data.csv", pos);
  Write("curr_data.csv", cur);
  const fs::path desc = Write("tx40.yaml",
                              "rate: 5000\n"
                              "files:\n"
                              "  - {path: pos_read_data.csv, columns: q1..q6}\n"
                              "  - path: curr_data.csv\n"
                              "    columns: [i1..i6]\n"
                              "angle_unit: deg\n"
                              "drive_gains: [2, 4, 8, 0.5, 0.25, 1]\n"
                              "time_window: [0.01, 0.09]\n");
  const double gains[] = {2, 4, 8, 0.5, 0.25, 1};
  const auto source = OpenJointLog(desc.string(), puma, {}, TorqueColumns::kRequired);
  EXPECT_EQ(source->layout().rate_hz, 5000.0);
  EXPECT_EQ(source->layout().time_window, (std::vector<double>{0.01, 0.09}));
  const RecordedJointLog r = ReadWholeLog(*source, 7);
  ASSERT_EQ(r.log.n_samples(), n);
  EXPECT_TRUE(r.torque_from_currents);
  for (int k = 0; k < n; ++k) {
    ASSERT_EQ(r.log.t[k], k / 5000.0);
    for (int j = 0; j < 6; ++j) {
      // The degrees written round-trip exactly; the reader's conversion is × π/180.
      ASSERT_EQ(r.log.q(k, j), (Q(k, j) * 180.0 / M_PI) * (M_PI / 180.0));
      ASSERT_NEAR(r.log.q(k, j), Q(k, j), 1e-15);
      ASSERT_EQ(r.log.tau(k, j), gains[j] * Tau(k, j));
    }
  }
  EXPECT_EQ(r.lines.front(), 2);  // after the header
  bool renamed = false;
  for (const std::string& note : r.notes) renamed = renamed || note.find("'Joint_1' → q1") != std::string::npos;
  EXPECT_TRUE(renamed);
  // The same options given again on the command line: refused, both named.
  JointLogFormat deg;
  deg.angle_unit = "deg";
  EXPECT_EQ(ExpectInvalid([&] { OpenJointLog(desc.string(), puma, deg, TorqueColumns::kRequired); }),
            desc.string() + ": .angle_unit (deg) and the option angle_unit (deg) both give the angle unit: give it in "
                            "one place");
  JointLogFormat gains_option;
  gains_option.drive_gains = std::vector<double>(6, 1.0);
  EXPECT_NE(ExpectInvalid([&] { OpenJointLog(desc.string(), puma, gains_option, TorqueColumns::kRequired); })
                .find(".drive_gains (2,4,8,0.5,0.25,1) and the option drive_gains (1,1,1,1,1,1) both give"),
            std::string::npos);
}

// Every error names the description and the field, or the file and line.
TEST_F(DescribedJointLogTest, ErrorsNameTheDescriptionFieldOrTheFileAndLine) {
  const RobotModel puma = MakePuma560();
  std::string six = "q1,q2,q3,q4,q5,q6\n", taus = "tau1,tau2,tau3,tau4,tau5,tau6\n";
  for (int k = 0; k < 4; ++k) {
    six += "0,0,0,0,0,0\n";
    taus += "1,1,1,1,1,1\n";
  }
  Write("q.csv", six);
  Write("tau.csv", taus);
  Write("tau5.csv", taus + "1,1,1,1,1,1\n");
  Write("bad.csv", "q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0\n0,0,x,0,0,0\n");
  Write("odd.txt", "1\n2\n3\n4\n5\n6\n7\n");
  Write("motor.csv", "J1,J2,J3,J4,J5,J6\n0,0,0,0,0,0\n");
  auto open = [&](const std::string& name, const std::string& text) {
    const fs::path desc = Write(name, text);
    return ExpectInvalid([&] {
      const auto source = OpenJointLog(desc.string(), puma, {}, TorqueColumns::kRequired);
      ReadWholeLog(*source, 3);
    });
  };
  const std::string d = (dir_ / "d.json").string();
  const std::string q = R"({"path": "q.csv"})", tau = R"({"path": "tau.csv"})";
  struct Case {
    std::string text, expected;
  };
  const std::vector<Case> cases = {
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "rat": 1})", d + ": .rat: unknown key; expected \"rate\", \"files\""},
      {R"({"rate": 100, "files": [{"path": "q.csv", "stide": 6}]})", d + ": .files[0].stide: unknown key; expected \"path\""},
      {R"({"rate": 0, "files": [)" + q + "]}", d + ": .rate: expected a sampling rate in Hz, 1 to 1e+06, got 0"},
      {R"({"rate": 100, "files": []})", d + ": .files: expected a list of 1 to 16 files, got 0 files"},
      {R"({"rate": 100, "files": [)" + q + R"(, {"path": "odd.txt", "layout": "one-value-per-line", "stride": 2000, "columns": "_"}]})",
       d + ": .files[1].stride: expected a whole number 1 to 1024, got 2000"},
      {R"({"rate": 100, "files": [)" + q + R"(, {"path": "odd.txt", "layout": "one-value-per-line", "stride": 6, "columns": "tau1..tau5"}]})",
       d + ": .files[1].columns: names 5 columns but \"stride\" is 6"},
      {R"({"rate": 100, "files": [)" + q + R"(, {"path": "odd.txt", "layout": "one-value-per-line", "stride": 6, "columns": "tau1..tau6"}]})",
       (dir_ / "odd.txt").string() + ":7: the file ends within a sample: 1 of its 6 lines (stride 6)"},
      {R"({"rate": 100, "files": [)" + q + R"(, {"path": "tau5.csv"}]})",
       d + ": .files[0] (q.csv) has 4 samples but .files[1] (tau5.csv) has 5: the files are joined sample by sample"},
      {R"({"rate": 100, "files": [{"path": "bad.csv"}, )" + tau + "]}",
       (dir_ / "bad.csv").string() + ":3: column 3 ('q3'): 'x' is not a number"},
      {R"({"rate": 100, "files": [{"path": "motor.csv", "columns": "qm1..qm6"}, )" + tau + "]}",
       d + ": .files[0].columns: column 1 ('qm1'): motor position (an actuator-side column): reading it needs the "
           "transmission"},
      {R"({"files": [)" + q + "," + tau + "]}", d + ": no time: give .rate"},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "transmission": {"reductions": [1]}})",
       d + ": .transmission.reductions: unknown key; expected \"reduction\", \"actuator_from_joint\", \"joint_offset\""},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "transmission": {"joint_offset": [0]}})",
       d + ": .transmission: expected \"reduction\": [N1, ...] (gear ratios) or \"actuator_from_joint\""},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "transmission": {"reduction": [32, 32, 0, 1, 1, 1]}})",
       d + ": .transmission.reduction[2]: expected a non-zero gear ratio (θm = N·q), got 0"},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "transmission": {"reduction": [32, 32, -1e77, 1, 1, 1]}})",
       d + ": .transmission.reduction[2]: expected a gear ratio of magnitude at most 10000 (beyond any drive), got -1e+77"},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "transmission": {"reduction": [32, 32, 45]}})",
       d + ": .transmission: 3 actuators, the robot has 6 joints (one actuator each)"},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "transmission": {"actuator_from_joint": [[1, 2], [3]]}})",
       d + ": .transmission.actuator_from_joint[1]: expected 2 values (a square matrix, one row per actuator), got 1"},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "transmission": {"actuator_from_joint": [[1, 2], [2, 4]]}})",
       d + ": .transmission.actuator_from_joint: not invertible"},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "transmission": {"reduction": [1, 1, 1, 1, 1, 1], "joint_offset": [0, "x"]}})",
       d + ": .transmission.joint_offset[1]: expected a number, got \"x\""},
      {R"({"rate": 100, "files": [{"path": "motor.csv", "columns": "qm1..qm5,q6"}, )" + tau + R"(], "transmission": {"reduction": [1, 1, 1, 1, 1, 1]}})",
       d + ": .files: columns q* on the joint side and on the actuator side: give each kind on one side"},
      {R"({"rate": 100, "files": [)" + q + "]}", d + ": .files: missing column 'tau1' (robot has 6 joints)"},
      {R"({"rate": 100, "files": [)" + q + "," + q + "]}", d + ": column 'q1' is in both .files[0] (q.csv) and .files[1] (q.csv)"},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "angle_unit": "grad"})", d + ": .angle_unit: expected \"rad\" or \"deg\", got \"grad\""},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "time_window": [2, 1]})", d + ": .time_window: expected [T0, T1] [s] with T0 < T1"},
      {R"({"rate": 100, "files": [)" + q + "," + tau + R"(], "drive_gains": [1, 0]})", d + ": .drive_gains: joint 2: expected a gain of magnitude"},
      {R"({"rate": 100, "files": [{"path": "none.csv"}]})", d + ": .files[0].path: 'none.csv', taken in the description's folder " + dir_.string() + ": cannot read the file (No such file or directory)"},
      {R"({"rate": 100, "files": [)", d + ": not valid JSON: parse error at line 1, column 25"},
  };
  for (const Case& c : cases) {
    const std::string what = open("d.json", c.text);
    EXPECT_EQ(what.find(c.expected), 0u) << what << "\n  expected: " << c.expected;
  }
  const std::string yaml = open("d.yaml", "rate: 100\nfiles:\n  - path: q.csv\n  - {path: tau.csv\n");
  EXPECT_EQ(yaml.find((dir_ / "d.yaml").string() + ":5:1: not valid YAML"), 0u) << yaml;
  // Actuator-side columns in a CSV's own header are refused the same way.
  const std::string header = ExpectInvalid([&] {
    ParseRecordedJointLog("t,qm1,qm2,qm3,qm4,qm5,qm6\n0,0,0,0,0,0,0\n", puma, "m.csv", {}, TorqueColumns::kRequired);
  });
  EXPECT_EQ(header.find("m.csv:1: column 2 ('qm1'): motor position (an actuator-side column)"), 0u) << header;
}

// Issue 35 item 20: a file that cannot be read names the description, the
// field and the folder its relative path was taken in: the folder of the
// description as given (a symlink's own), not of the file it points to. On
// 1c4dd0f: "nope.csv: cannot read the file", nothing else.
TEST_F(DescribedJointLogTest, UnreadableFileNamesTheFieldAndTheFolder) {
  fs::create_directories(dir_ / "real");
  Write("real/q.csv", "q1,q2,q3,q4,q5,q6\n0,0,0,0,0,0\n");
  Write("real/d.json", R"({"rate": 100, "files": [{"path": "q.csv"}, {"path": "nope.csv"}]})");
  fs::create_symlink(dir_ / "real" / "d.json", dir_ / "link.json");
  const std::string link = (dir_ / "link.json").string();
  EXPECT_EQ(ExpectInvalid([&] { OpenJointLog(link, MakePuma560(), {}, TorqueColumns::kRequired); }),
            link + ": .files[0].path: 'q.csv', taken in the description's folder " + dir_.string() +
                ": cannot read the file (No such file or directory)");
  const std::string real = (dir_ / "real" / "d.json").string();
  EXPECT_EQ(ExpectInvalid([&] { OpenJointLog(real, MakePuma560(), {}, TorqueColumns::kRequired); }),
            real + ": .files[1].path: 'nope.csv', taken in the description's folder " + (dir_ / "real").string() +
                ": cannot read the file (No such file or directory)");
  // An absolute path is named as it is.
  const fs::path absolute = Write("abs.json", R"({"rate": 100, "files": [{"path": ")" + (dir_ / "gone.csv").string() + R"("}]})");
  EXPECT_EQ(ExpectInvalid([&] { OpenJointLog(absolute.string(), MakePuma560(), {}, TorqueColumns::kRequired); }),
            absolute.string() + ": .files[0].path: '" + (dir_ / "gone.csv").string() +
                "': cannot read the file (No such file or directory)");
}

// Issue 35 item 27: positions on the actuator side (qm*) in one file and on
// the joint side (q*) in another are named as written, each with its side
// (1c4dd0f: "column 'q1' is in both ...", a name neither file has twice).
TEST_F(DescribedJointLogTest, ActuatorAndJointSideOfOneKindInTwoFilesAreNamedBySide) {
  Write("motor.csv", Lines("0,0,0,0,0,0", 3));
  Write("q.csv", Lines("0,0,0,0,0,0", 3));
  Write("tau.csv", Lines("1,1,1,1,1,1", 3));
  const std::string motor_file = R"({"path": "motor.csv", "columns": "qm1..qm6"})",
                    joint_file = R"({"path": "q.csv", "columns": "q1..q6"})",
                    tau_file = R"({"path": "tau.csv", "columns": "tau1..tau6"})";
  const auto refusal = [&](const std::string& files) {
    const fs::path desc = Write("d.json", R"({"rate": 100, "transmission": {"reduction": [1, 2, 3, 4, 5, 6]}, "files": [)" +
                                              files + "]}");
    return ExpectInvalid([&] { OpenJointLog(desc.string(), MakePuma560(), {}, TorqueColumns::kRequired); });
  };
  const std::string d = (dir_ / "d.json").string();
  EXPECT_EQ(refusal(motor_file + "," + joint_file + "," + tau_file),
            d + ": columns q* on the actuator side ('qm1' in .files[0] (motor.csv)) and on the joint side "
                "('q1' in .files[1] (q.csv)): give each kind on one side");
  EXPECT_EQ(refusal(tau_file + "," + joint_file + "," + motor_file),
            d + ": columns q* on the joint side ('q1' in .files[1] (q.csv)) and on the actuator side ('qm1' in "
                ".files[2] (motor.csv)): give each kind on one side");
}

// Issue 35 item 28: "skip" past the end of a 601-line file names the field,
// the count and the file's lines (1c4dd0f: "empty file"), for both layouts;
// a skip leaving one line reads it.
TEST_F(DescribedJointLogTest, SkipPastTheEndNamesTheFieldAndTheLineCount) {
  const std::string q_path = Write("q.csv", "q1,q2,q3,q4,q5,q6\n" + Lines("0,0,0,0,0,0", 600)).string(),
                    one_path = Write("one.txt", Lines("1", 601 * 6)).string();
  Write("tau.csv", Lines("1,1,1,1,1,1", 600));
  const RobotModel puma = MakePuma560();
  const auto open = [&](const std::string& text) {
    const fs::path desc = Write("d.json", text);
    return ExpectInvalid([&] { OpenJointLog(desc.string(), puma, {}, TorqueColumns::kRequired); });
  };
  const std::string d = (dir_ / "d.json").string();
  EXPECT_EQ(open(R"({"rate": 100, "files": [{"path": "q.csv", "skip": 1000000}, {"path": "tau.csv", "columns": "tau1..tau6"}]})"),
            d + ": .files[0].skip: skips 1000000 lines, but " + q_path + " has 601: nothing is left to read");
  EXPECT_EQ(open(R"({"rate": 100, "files": [{"path": "q.csv", "skip": 601}, {"path": "tau.csv", "columns": "tau1..tau6"}]})"),
            d + ": .files[0].skip: skips 601 lines, but " + q_path + " has 601: nothing is left to read");
  EXPECT_EQ(open(R"({"rate": 100, "files": [{"path": "q.csv"}, {"path": "one.txt", "layout": "one-value-per-line", "stride": 6, "columns": "tau1..tau6", "skip": 5000}]})"),
            d + ": .files[1].skip: skips 5000 lines, but " + one_path + " has 3606: nothing is left to read");
  // Skipping all but the last line leaves it to read.
  const fs::path last = Write("last.json", R"({"rate": 100, "files": [{"path": "q.csv", "skip": 600, "columns": "q1..q6"}, {"path": "tau.csv", "columns": "tau1..tau6"}]})");
  EXPECT_NO_THROW(OpenJointLog(last.string(), puma, {}, TorqueColumns::kRequired));
}

}  // namespace
}  // namespace idbench
