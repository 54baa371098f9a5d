#include "idbench/logs/joint_log_csv_reader.h"

#include <gtest/gtest.h>

#include "engine/test_util.h"

#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <cstdio>
#include <fstream>
#include <unistd.h>

#include "idbench/logs/recorded_joint_log_source.h"

#include "idbench/engine/puma560.h"

namespace idbench {
namespace {

using testing::ExpectInvalid;

// Header-less lines of a 6-joint log: t, q (0.1 j + t), qd (j), a target
// current to skip, i (−j), an extra column to ignore.
std::string HeaderlessText() {
  std::string text;
  for (int s = 0; s < 3; ++s) {
    const double t = 0.01 * s;
    text += std::to_string(t);
    for (int j = 1; j <= 6; ++j) text += "," + std::to_string(0.1 * j + t);
    for (int j = 1; j <= 6; ++j) text += "," + std::to_string(j);
    text += ",99";
    for (int j = 1; j <= 6; ++j) text += "," + std::to_string(-j);
    text += ",7,8\n";
  }
  return text;
}

TEST(JointLogCsvTest, ColumnsNameAHeaderlessFileWithRangesSkipsAndGains) {
  const RobotModel puma = MakePuma560();
  JointLogFormat format;
  format.columns = {"t", "q1..q6", "qd1..qd6", "_", "i1..i6"};
  format.drive_gains = {10, 20, 30, 40, 50, 60};
  const RecordedJointLog r = ParseRecordedJointLog(HeaderlessText(), puma, "ur.csv", format, TorqueColumns::kRequired);
  ASSERT_EQ(r.log.n_samples(), 3);
  EXPECT_EQ(r.lines, (std::vector<int>{1, 2, 3}));
  EXPECT_TRUE(r.torque_from_currents);
  EXPECT_EQ(r.log.qdd.size(), 0);  // not recorded: estimated later
  for (int j = 0; j < 6; ++j) {
    EXPECT_DOUBLE_EQ(r.log.t[2], 0.02);
    EXPECT_DOUBLE_EQ(r.log.q(2, j), 0.1 * (j + 1) + 0.02);
    EXPECT_DOUBLE_EQ(r.log.qd(1, j), j + 1.0);
    EXPECT_DOUBLE_EQ(r.log.tau(0, j), -(j + 1.0) * format.drive_gains[j]);  // τ = K·i
  }
  // For the gains: the currents themselves.
  format.drive_gains.clear();
  const RecordedJointLog currents = ParseRecordedJointLog(HeaderlessText(), puma, "ur.csv", format, TorqueColumns::kCurrents);
  EXPECT_DOUBLE_EQ(currents.log.tau(0, 3), -4.0);
  EXPECT_FALSE(currents.torque_from_currents);
  EXPECT_EQ(ExpandColumnNames({"t", "tau2..tau4", "_"}), (std::vector<std::string>{"t", "tau2", "tau3", "tau4", "_"}));
}

// --columns overrides a header line (skipped); degrees become radians before
// the joint-limit check.
TEST(JointLogCsvTest, ColumnsOverrideAHeaderAndDegreesAreConverted) {
  const RobotModel puma = MakePuma560();
  JointLogFormat format;
  format.columns = {"t", "q1..q6", "tau1..tau6"};
  format.angle_unit = "deg";
  const std::string text = "time,a,b,c,d,e,f,g,h,i,j,k,l\n0,90,0,0,0,0,0,1,2,3,4,5,6\n0.5,45,0,0,0,0,0,1,2,3,4,5,6\n";
  const RecordedJointLog r = ParseRecordedJointLog(text, puma, "deg.csv", format, TorqueColumns::kRequired);
  ASSERT_EQ(r.log.n_samples(), 2);
  EXPECT_EQ(r.lines, (std::vector<int>{2, 3}));
  EXPECT_DOUBLE_EQ(r.log.q(0, 0), std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(r.log.q(1, 0), std::numbers::pi / 4);
  EXPECT_DOUBLE_EQ(r.log.tau(1, 5), 6.0);
  // 170 deg is inside puma joint 1's limits in rad (±2.79) but 170 rad is not.
  const std::string far = "0,200,0,0,0,0,0,1,2,3,4,5,6\n";
  EXPECT_NE(ExpectInvalid([&] { ParseRecordedJointLog(far, puma, "deg.csv", format, TorqueColumns::kRequired); })
                .find("deg.csv:1: column 2 ('q1'): 200 deg (3.49"),
            std::string::npos);
  format.angle_unit = "rad";
  EXPECT_NE(ExpectInvalid([&] {
              ParseRecordedJointLog("0,2,0,0,0,0,0,1,2,3,4,5,6\n1,2.5,0,0,0,0,0,1,2,3,4,5,6\n1.5,9,0,0,0,0,0,1,2,3,4,5,6\n",
                                    puma, "rad.csv", format, TorqueColumns::kRequired);
            }).find("rad.csv:3: column 2 ('q1'): 9 rad is outside joint 1's limits"),
            std::string::npos);
}

// With a header: any subset of qd, qdd; tau and currents both present with
// gains: K·i wins, with a warning.
TEST(JointLogCsvTest, HeaderWithMeasuredVelocityAndBothTorqueKinds) {
  const RobotModel puma = MakePuma560();
  const std::string text =
      "t,q1,q2,q3,q4,q5,q6,qd1,qd2,qd3,qd4,qd5,qd6,tau1,tau2,tau3,tau4,tau5,tau6,i1,i2,i3,i4,i5,i6\n"
      "0,0,0,0,0,0,0,1,1,1,1,1,1,5,5,5,5,5,5,2,2,2,2,2,2\n";
  const RecordedJointLog plain = ParseRecordedJointLog(text, puma, "p.csv", {}, TorqueColumns::kRequired);
  EXPECT_EQ(plain.log.qd.rows(), 1);
  EXPECT_EQ(plain.log.qdd.size(), 0);
  EXPECT_EQ(plain.log.tau(0, 0), 5.0);
  EXPECT_TRUE(plain.warnings.empty());
  JointLogFormat gains;
  gains.drive_gains = std::vector<double>(6, 3.0);
  const RecordedJointLog scaled = ParseRecordedJointLog(text, puma, "p.csv", gains, TorqueColumns::kRequired);
  EXPECT_EQ(scaled.log.tau(0, 0), 6.0);
  ASSERT_EQ(scaled.warnings.size(), 1u);
  EXPECT_NE(scaled.warnings[0].find("tau columns ignored"), std::string::npos);
  // The trajectory reader still wants qd and qdd together.
  EXPECT_NE(ExpectInvalid([&] { ParseJointLogCsv(text, puma, "p.csv"); }).find("qd1' without qdd1"), std::string::npos);
}

TEST(JointLogCsvTest, ErrorsNameFileLineAndColumnOrTheOption) {
  const RobotModel puma = MakePuma560();
  auto parse = [&](const std::string& text, const JointLogFormat& format, TorqueColumns torques = TorqueColumns::kRequired) {
    return ExpectInvalid([&] { ParseRecordedJointLog(text, puma, "x.csv", format, torques); });
  };
  JointLogFormat currents;
  currents.columns = {"t", "q1..q6", "i1..i6"};
  const std::string data = "0,0,0,0,0,0,0,1,1,1,1,1,1\n";
  struct Case {
    std::string text;
    JointLogFormat format;
    std::string expected;
  };
  JointLogFormat short_columns;
  short_columns.columns = {"t", "q1..q6", "tau1..tau6", "_"};
  JointLogFormat bad_range;
  bad_range.columns = {"t", "q1..qd6"};
  JointLogFormat seven;
  seven.columns = {"t", "q1..q7", "tau1..tau6"};
  const std::vector<Case> cases = {
      {data, {}, "x.csv:1: the first line is data (all numbers), not a header naming the columns: pass `columns`"},
      {data, currents, "x.csv: columns: the log has motor currents i1..i6 but no tau: pass drive_gains"},
      {data, short_columns, "x.csv:1: 13 fields, expected at least 14"},
      {data, bad_range, "columns: 'q1..qd6': expected a range such as q1..q6"},
      {data, seven, "columns: column 8 ('q7'): joint 7 but the robot has 6 joints"},
      {"t,q1,q2,q3,q4,q5,q6,qd1,qd2,tau1,tau2,tau3,tau4,tau5,tau6\n", {}, "x.csv:1: missing column 'qd3': give all of qd1..qd6 or none"},
      {"t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n0,0,0,0,0,0,0,1,1,1,1,x,1\n", {}, "x.csv:2: column 12 ('tau5'): 'x' is not a number"},
  };
  for (const Case& c : cases) {
    const std::string what = parse(c.text, c.format);
    EXPECT_NE(what.find(c.expected), std::string::npos) << what;
  }
  EXPECT_NO_THROW(ParseRecordedJointLog(data, puma, "x.csv", currents, TorqueColumns::kCurrents));
  JointLogFormat gains_without_currents;
  gains_without_currents.drive_gains = std::vector<double>(6, 1.0);
  EXPECT_NE(parse("t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n0,0,0,0,0,0,0,1,1,1,1,1,1\n", gains_without_currents)
                .find("x.csv:1: drive_gains given but the log has no motor currents i1..i6"),
            std::string::npos);
  // Options alone: the CLI reports these as usage errors.
  std::string why;
  JointLogFormat unit;
  unit.angle_unit = "grad";
  EXPECT_FALSE(unit.IsValid(&why));
  EXPECT_NE(why.find("angle_unit: expected rad or deg"), std::string::npos);
  JointLogFormat zero_gain;
  zero_gain.drive_gains = {1, 0};
  EXPECT_FALSE(zero_gain.IsValid(&why));
  EXPECT_NE(why.find("drive_gains: joint 2"), std::string::npos) << why;
  zero_gain.drive_gains = {1, 2};
  EXPECT_TRUE(zero_gain.IsValid(&why));
  EXPECT_FALSE(zero_gain.IsValidFor(6, &why));
  EXPECT_NE(why.find("2 gains, the robot has 6 joints"), std::string::npos);
  JointLogFormat too_many;
  too_many.columns = {"t", "q1..q2000"};
  EXPECT_FALSE(too_many.IsValid(&why));
  EXPECT_NE(why.find("more than 1024 columns"), std::string::npos) << why;
}

// A header t, q, qd, qdd, tau of a 6-joint log in which each field holds its
// own column number plus 100 × the sample (so every read can be traced to
// its column), and that number for a column c.
std::string NumberedFullLog() {
  std::string text = "t";
  for (const char* prefix : {"q", "qd", "qdd", "tau"})
    for (int j = 1; j <= 6; ++j) text += "," + std::string(prefix) + std::to_string(j);
  text += "\n";
  for (int s = 0; s < 2; ++s) {
    text += std::to_string(s);  // t
    for (int c = 1; c < 25; ++c) text += "," + std::to_string(c < 7 ? 0.01 * c : c + 100.0 * s);
    text += "\n";
  }
  return text;
}

// A columns list naming a subset of an idbench header is matched by name
// (6ab1a0b read it by position: tau from the qd columns); a note says so.
TEST(JointLogCsvTest, ColumnsNamingASubsetOfTheHeaderAreMatchedByName) {
  const RobotModel puma = MakePuma560();
  JointLogFormat format;
  format.columns = {"t", "q1..q6", "tau1..tau6"};
  const RecordedJointLog r = ParseRecordedJointLog(NumberedFullLog(), puma, "full.csv", format, TorqueColumns::kRequired);
  ASSERT_EQ(r.log.n_samples(), 2);
  EXPECT_EQ(r.log.qd.size(), 0);  // not named: estimated later
  for (int j = 0; j < 6; ++j) {
    EXPECT_DOUBLE_EQ(r.log.q(1, j), 0.01 * (j + 1));
    EXPECT_DOUBLE_EQ(r.log.tau(1, j), 19 + j + 100.0);  // file column 20 + j, counted from 1
  }
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0], "full.csv: columns t,q1..q6,tau1..tau6 taken by name from the header (13 of its 25 columns; "
                        "the others are not used)");
  // A list that agrees with the header ("_" skips) is read as named, no note.
  format.columns = {"t", "q1..q6", "_", "_", "_", "_", "_", "_", "qdd1..qdd6", "tau1..tau6"};
  const RecordedJointLog agreed = ParseRecordedJointLog(NumberedFullLog(), puma, "full.csv", format, TorqueColumns::kRequired);
  EXPECT_DOUBLE_EQ(agreed.log.qdd(0, 2), 15.0);
  EXPECT_DOUBLE_EQ(agreed.log.tau(0, 2), 21.0);
  EXPECT_TRUE(agreed.notes.empty());
}

// A list that contradicts an idbench header: an error naming both names
// (6ab1a0b: qdd and tau swapped were read silently).
TEST(JointLogCsvTest, ColumnsContradictingTheHeaderAreRefused) {
  const RobotModel puma = MakePuma560();
  auto parse = [&](const std::vector<std::string>& columns) {
    JointLogFormat format;
    format.columns = columns;
    return ExpectInvalid([&] { ParseRecordedJointLog(NumberedFullLog(), puma, "full.csv", format, TorqueColumns::kRequired); });
  };
  EXPECT_NE(parse({"t", "q1..q6", "qd1..qd6", "tau1..tau6", "qdd1..qdd6"})
                .find("full.csv:1: column 14 ('qdd1'): the header names this column 'qdd1' but the columns list names "
                      "it 'tau1': with a header that uses idbench's names"),
            std::string::npos);
  // A subset with a name the header lacks: both named.
  EXPECT_NE(parse({"t", "q1..q6", "i1..i6"}).find("the header names this column 'qd1' but the columns list names it "
                                                   "'i1' (and the header has no column 'i1')"),
            std::string::npos);
  EXPECT_NE(parse({"t", "q1..q6", "qd1..qd6", "qdd1..qdd6", "tau1..tau6", "_"})
                .find("full.csv:1: the columns list names 26 columns but the header has 25"),
            std::string::npos);
}

// A vendor's header is renamed by the list in order, and the note shows the
// mapping; joint names (q.<joint>, as trajectory.csv is headed) are read as
// the joint's number; a header naming joints the robot lacks is refused.
TEST(JointLogCsvTest, VendorHeadersJointNamesAndAnotherRobot) {
  const RobotModel puma = MakePuma560();
  JointLogFormat format;
  format.columns = {"t", "q1..q6", "tau1..tau6"};
  const std::string vendor = "time,Joint_1,Joint_2,Joint_3,Joint_4,Joint_5,Joint_6,M1,M2,M3,M4,M5,M6\n"
                             "0,0,0,0,0,0,0,1,2,3,4,5,6\n";
  const RecordedJointLog r = ParseRecordedJointLog(vendor, puma, "v.csv", format, TorqueColumns::kRequired);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0].find("v.csv: columns renames the header's columns in file order: 'time' → t, 'Joint_1' → q1, "
                            "'Joint_2' → q2"),
            0u) << r.notes[0];
  EXPECT_NE(r.notes[0].find("'M6' → tau6"), std::string::npos) << r.notes[0];
  EXPECT_DOUBLE_EQ(r.log.tau(0, 4), 5.0);
  // Joint names, in another order than the robot's: each read as its joint.
  std::string named = "t";
  for (int j = 5; j >= 0; --j) named += ",q." + puma.link(j).joint_name;
  for (int j = 0; j < 6; ++j) named += ",tau." + puma.link(j).joint_name;
  named += "\n0,0.6,0.5,0.4,0.3,0.2,0.1,1,2,3,4,5,6\n";
  const RecordedJointLog by_name = ParseRecordedJointLog(named, puma, "n.csv", {}, TorqueColumns::kRequired);
  for (int j = 0; j < 6; ++j) {
    EXPECT_DOUBLE_EQ(by_name.log.q(0, j), 0.1 * (j + 1));
    EXPECT_DOUBLE_EQ(by_name.log.tau(0, j), j + 1.0);
  }
  EXPECT_NE(ExpectInvalid([&] {
              ParseRecordedJointLog("t,q.elbow_joint\n0,0\n", puma, "ur.csv", {}, TorqueColumns::kRequired);
            }).find("ur.csv:1: column 2 ('q.elbow_joint'): no joint 'elbow_joint' in puma560"),
            std::string::npos);
  // 5 joints in the header: another robot too.
  EXPECT_NE(ExpectInvalid([&] {
              ParseRecordedJointLog("t,q1,q2,q3,q4,q5,tau1,tau2,tau3,tau4,tau5\n0,0,0,0,0,0,1,1,1,1,1\n", puma, "f.csv",
                                    {}, TorqueColumns::kRequired);
            }).find("f.csv:1: missing column 'q6' (robot has 6 joints): the header names joints 1 to 5 only: is this a log "
                  "of another robot?"),
            std::string::npos);
  // 7 joints in the header: another robot, even when the list names 6.
  std::string seven = "t";
  for (const char* p : {"q", "tau"})
    for (int j = 1; j <= 7; ++j) seven += "," + std::string(p) + std::to_string(j);
  seven += "\n0,0,0,0,0,0,0,0,1,1,1,1,1,1,1\n";
  for (const JointLogFormat& f : {JointLogFormat{}, format}) {
    EXPECT_NE(ExpectInvalid([&] { ParseRecordedJointLog(seven, puma, "s.csv", f, TorqueColumns::kRequired); })
                  .find("s.csv:1: column 8 ('q7'): the header names joint 7 but puma560 has 6 joints: is this a log "
                        "of another robot?"),
              std::string::npos);
  }
}

// With angle_unit deg, a log whose joints all move less than 5° draws a
// warning (a log in radians read as degrees); a real degree log does not.
TEST(JointLogCsvTest, RadiansReadAsDegreesAreWarnedAbout) {
  const RobotModel puma = MakePuma560();
  JointLogFormat deg;
  deg.angle_unit = "deg";
  const std::string header = "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n";
  const RecordedJointLog radians = ParseRecordedJointLog(
      header + "0,0,0,0,0,0,0,1,1,1,1,1,1\n1,1.5,-1,0.5,0,0,0,1,1,1,1,1,1\n", puma, "r.csv", deg, TorqueColumns::kRequired);
  ASSERT_EQ(radians.warnings.size(), 1u);
  EXPECT_NE(radians.warnings[0].find("r.csv: with angle_unit deg no joint moves more than 1.5° over the log"),
            std::string::npos) << radians.warnings[0];
  const RecordedJointLog degrees = ParseRecordedJointLog(
      header + "0,0,0,0,0,0,0,1,1,1,1,1,1\n1,80,-40,30,0,0,0,1,1,1,1,1,1\n", puma, "d.csv", deg, TorqueColumns::kRequired);
  EXPECT_TRUE(degrees.warnings.empty());
}

// A UTF-8 byte order mark before the header is skipped (it made "unknown
// column 't'" with the mark invisible); a column name that is not text is
// echoed escaped and cut; a line over the limit is refused before splitting.
TEST(JointLogCsvTest, ByteOrderMarkBinaryNamesAndLongLines) {
  const RobotModel puma = MakePuma560();
  std::string header = "t";
  for (const char* kind : {"q", "tau"}) {
    for (int j = 1; j <= 6; ++j) header += std::string(",") + kind + std::to_string(j);
  }
  const std::string rows = "0,0,0,0,0,0,0,1,1,1,1,1,1\n0.01,0,0,0,0,0,0,1,1,1,1,1,1\n";
  const RecordedJointLog with_bom =
      ParseRecordedJointLog("\xef\xbb\xbf" + header + "\n" + rows, puma, "x.csv", {}, TorqueColumns::kRequired);
  const RecordedJointLog without =
      ParseRecordedJointLog(header + "\n" + rows, puma, "x.csv", {}, TorqueColumns::kRequired);
  EXPECT_EQ(with_bom.log.t, without.log.t);
  EXPECT_EQ(with_bom.log.tau, without.log.tau);
  EXPECT_EQ(with_bom.lines, without.lines);

  // 64 bytes shown: 3 escaped, then 61 BELs escaped.
  const std::string binary = std::string("\x01\x02\xff") + std::string(5000, '\x07');
  std::string shown = "\\x01\\x02\\xff";
  for (int k = 0; k < 61; ++k) shown += "\\x07";
  EXPECT_EQ(ExpectInvalid([&] {
              ParseRecordedJointLog(binary + "," + header + "\n" + rows, puma, "x.csv", {}, TorqueColumns::kRequired);
            }),
            "x.csv:1: column 1 ('" + shown +
                "… (5003 bytes)'): unknown column; expected t, q1..q6, qd*, qdd*, tau*, i* (motor current)");

  const std::string long_line = header + "," + std::string(70000, '9') + "\n" + rows;
  EXPECT_EQ(ExpectInvalid([&] { ParseRecordedJointLog(long_line, puma, "x.csv", {}, TorqueColumns::kRequired); }),
            "x.csv:1: the line is " + std::to_string(header.size() + 1 + 70000) +
                " bytes, longer than the limit for a line, 64 KB (1024 columns of 64 characters; "
                "IDBENCH_MAX_LINE_KB=N raises it to N KB)");
}

}  // namespace
}  // namespace idbench

namespace idbench {
namespace {

// The streamed reader (OpenJointLogCsv) in chunks of 1, 7 and 65 536 samples
// gives what the whole-text reader gives, on the texts above; and on a log of
// 40 000 samples (2.6 MB, across the 1 MiB blocks) written by an independent
// writer ("%.17g"), the known values exactly.
TEST(JointLogCsvTest, StreamedInChunksEqualsTheWholeReader) {
  const RobotModel puma = MakePuma560();
  JointLogFormat headerless;
  headerless.columns = {"t", "q1..q6", "qd1..qd6", "_", "i1..i6"};
  headerless.drive_gains = {10, 20, 30, 40, 50, 60};
  JointLogFormat subset;
  subset.columns = {"t", "q1..q6", "tau1..tau6"};
  std::string big = "t,q1,q2,q3,q4,q5,q6,qd1,qd2,qd3,qd4,qd5,qd6,tau1,tau2,tau3,tau4,tau5,tau6\n";
  constexpr int kBig = 40000;
  char number[32];
  auto value = [](int k, int c) { return c == 0 ? 1e-3 * k : 0.4 * std::sin(1e-3 * k * c) + 1e-17 * c; };
  for (int k = 0; k < kBig; ++k) {
    for (int c = 0; c < 19; ++c) {
      std::snprintf(number, sizeof(number), "%.17g", value(k, c));
      big += std::string(c ? "," : "") + number;
    }
    big += "\n";
  }
  const std::vector<std::pair<std::string, JointLogFormat>> logs = {
      {HeaderlessText(), headerless}, {NumberedFullLog(), {}}, {NumberedFullLog(), subset}, {big, {}}};
  const std::string path = ::testing::TempDir() + "/streamed_" + std::to_string(::getpid()) + ".csv";
  for (const auto& [text, format] : logs) {
    std::ofstream(path) << text;
    const RecordedJointLog whole = ParseRecordedJointLog(text, puma, path, format, TorqueColumns::kRequired);
    for (const Eigen::Index chunk : {Eigen::Index{1}, Eigen::Index{7}, Eigen::Index{65536}}) {
      const auto source = OpenJointLogCsv(path, puma, format, TorqueColumns::kRequired);
      for (int pass = 0; pass < 2; ++pass) {  // and again after Rewind
        const RecordedJointLog streamed = ReadWholeLog(*source, chunk);
        EXPECT_EQ(streamed.log.t, whole.log.t);
        EXPECT_EQ(streamed.log.q, whole.log.q);
        EXPECT_EQ(streamed.log.qd, whole.log.qd);
        EXPECT_EQ(streamed.log.tau, whole.log.tau);
        EXPECT_EQ(streamed.lines, whole.lines);
        EXPECT_EQ(streamed.notes, whole.notes);
        source->Rewind();
      }
    }
  }
  std::remove(path.c_str());
  const RecordedJointLog r = ParseRecordedJointLog(big, puma, "big.csv", {}, TorqueColumns::kRequired);
  ASSERT_EQ(r.log.n_samples(), kBig);
  for (int k = 0; k < kBig; k += 997) {
    EXPECT_EQ(r.log.t[k], value(k, 0));
    for (int j = 0; j < 6; ++j) {
      EXPECT_EQ(r.log.q(k, j), value(k, 1 + j));
      EXPECT_EQ(r.log.qd(k, j), value(k, 7 + j));
      EXPECT_EQ(r.log.tau(k, j), value(k, 13 + j));
    }
  }
  // Bad data deep in the file: the line, in whichever chunk it falls.
  std::string bad = big;
  bad.replace(bad.rfind('\n', bad.size() - 2) + 1, 1, "x");
  std::ofstream(path) << bad;
  const auto source = OpenJointLogCsv(path, puma, {}, TorqueColumns::kRequired);
  EXPECT_EQ(ExpectInvalid([&] { ReadWholeLog(*source, 7); }).find(path + ":" + std::to_string(kBig + 1) + ": column 1 ('t'): 'x"),
            0u);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace idbench
