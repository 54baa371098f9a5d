// The Design tab's cell and mounting driven headless: a scene file's box
// beside the robot is drawn in the viewport (pixels of the obstacles' sand
// colour appear where there were none), a bad scene file is named with its
// field in the messages, and a design in the cell on a moved base, or with a
// motor limit through a transmission, equals RunDesign on the same options
// (the command line's call).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "idbench/engine/puma560.h"
#include "idbench/engine/robot_library.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/gui/gui_script.h"
#include "idbench/gui/headless_gui.h"
#include "workbench/geared_paper6r.h"
#include "ident/synthetic_log.h"
#include "workbench/gui/gui_test_util.h"

namespace idbench::gui {
namespace {

namespace fs = std::filesystem;

fs::path DesignTabDir(const std::string& name) { return gui::TempDir("design_tab_test", name); }

// Pixels of the viewport in the obstacles' sand (0.74, 0.69, 0.60) lit: red
// above green above blue, not grey, not a link colour (the test of
// render_cli_test's SceneAndBasePoseAreDrawn).
long long SandPixels(HeadlessGui& gui) {
  const WidgetEntry* viewport = gui.widgets().Find("viewport");
  if (!viewport) return -1;
  const Image image = gui.Screenshot();
  long long n = 0;
  for (int v = static_cast<int>(viewport->rect.y0); v < static_cast<int>(viewport->rect.y1); ++v) {
    for (int u = static_cast<int>(viewport->rect.x0); u < static_cast<int>(viewport->rect.x1); ++u) {
      const std::uint8_t* p = image.at(u, v);
      n += p[0] > p[1] + 4 && p[1] > p[2] + 8 && p[0] - p[2] < 60;
    }
  }
  return n;
}

long long ViewportPixels(HeadlessGui& gui) {
  const WidgetRect& r = gui.widgets().Find("viewport")->rect;
  return static_cast<long long>(r.width()) * static_cast<long long>(r.height());
}

// A limits file (limits_file.h) for six joints, each with `joint`'s limits,
// and the motors' `actuators`.
void WriteLimitsFile(const fs::path& path, const std::string& joint, const std::string& actuators) {
  std::string joints;
  for (int j = 0; j < 6; ++j) joints += (j ? ", " : "") + joint;
  std::ofstream(path) << "{\"joints\": [" << joints << "], \"actuators\": " << actuators << "}";
}

TEST(DesignTabTest, SceneIsDrawnAndItsErrorsNamed) {
  const fs::path out = DesignTabDir("draw");
  const fs::path scene = out / "cell.json";
  std::ofstream(scene) << R"({"obstacles": [{"name": "pillar", "type": "box", "size": [0.6, 0.6, 1.2],
                              "pose": [-0.8, -0.8, 0.6, 0, 0, 0]}]})";
  const fs::path bad = out / "bad.json";
  std::ofstream(bad) << R"({"obstacles": [{"type": "sphere", "radius": -0.2, "pose": [0, 0, 1, 0, 0, 0]}]})";
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  RunScript(gui, "frames 2\n");
  const long long plain = SandPixels(gui);
  RunScript(gui, "click tab.design\nset design.scene " + scene.string() + "\nframes 2\n");
  const long long celled = SandPixels(gui);
  std::printf("sand pixels in the viewport: %lld plain, %lld with the box (of %lld)\n", plain, celled,
              ViewportPixels(gui));
  EXPECT_LT(plain, 0.005 * ViewportPixels(gui));
  EXPECT_GT(celled - plain, 0.03 * ViewportPixels(gui));
  EXPECT_EQ(gui.session().last_error(), "");

  // A bad file: its path and the field in the messages, no obstacle drawn.
  RunScript(gui, "set design.scene " + bad.string() + "\nframes 2\n");
  const std::string error = gui.session().last_error();
  EXPECT_NE(error.find("design.scene: "), std::string::npos) << error;
  EXPECT_NE(error.find(bad.string()), std::string::npos) << error;
  EXPECT_NE(error.find("obstacles[0].radius"), std::string::npos) << error;
  EXPECT_LT(SandPixels(gui), 0.005 * ViewportPixels(gui));
  // A base pose that is not six numbers is refused, naming it; the pose kept.
  std::string why;
  EXPECT_FALSE(gui.Set("design.base_pose", "0,0,1", &why));
  EXPECT_NE(why.find("base_pose"), std::string::npos) << why;
  EXPECT_TRUE(gui.session().design.design.base_pose.IsIdentity());
  if (!HasFailure()) fs::remove_all(out);
}

// A design in a cell (a pillar beside the robot) on a base raised and turned:
// the GUI's job equals RunDesign on the same options and limits, keeps the
// clearance to the pillar, and compare gets the same cell and mounting.
TEST(DesignTabTest, DesignInTheCellEqualsRunDesign) {
  const fs::path out = DesignTabDir("design");
  const fs::path scene = out / "cell.json";
  std::ofstream(scene) << R"({"obstacles": [{"name": "pillar", "type": "box", "size": [0.4, 0.4, 1.5],
                              "pose": [-1.0, -1.0, 0.75, 0, 0, 0]}]})";
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.design\nclick limits.fill\nset design.scene " + scene.string() +
                     "\nset design.base_pose 0,0,0.2,0,0,0.5\nset design.harmonics 2\nset design.f0 0.5\n"
                     "set design.samples 40\nset design.max_evaluations 20\nclick design.run\nwait design 300\n");
  ASSERT_TRUE(session.design_report().has_value()) << session.last_error();
  EXPECT_EQ(session.design.scene, scene.string());
  EXPECT_EQ(session.design.design.base_pose.xyz_rpy, (std::array<double, 6>{0, 0, 0.2, 0, 0, 0.5}));
  const DesignResult& shown = session.design_report()->result;
  DesignCommandOptions options = session.design;
  const DesignCommandReport direct = RunDesign(session.model(), options, session.limits, DesignControl{});
  EXPECT_EQ(shown.value, direct.result.value);
  EXPECT_EQ(shown.final.cond, direct.result.final.cond);
  ASSERT_EQ(shown.check.margins.size(), direct.result.check.margins.size());
  // The pillar is among the clearance pairs checked, and kept.
  int pillar = 0;
  for (const ConstraintMargin& m : shown.check.margins) {
    if (m.quantity != "clearance" || m.pair.find("pillar") == std::string::npos) continue;
    ++pillar;
    EXPECT_GE(m.margin, 0.0) << m.pair;
  }
  EXPECT_GT(pillar, 0);
  std::printf("design in the cell: criterion %.17g (RunDesign %.17g), %d pillar margins\n", shown.value,
              direct.result.value, pillar);
  if (!HasFailure()) fs::remove_all(out);
}

// A pillar around the arm leaves it no room (DesignStatus::kNoRoom): the GUI
// says "design failed: " and RunDesign's explanation, word for word, and
// keeps no design.
TEST(DesignTabTest, ACellWithoutRoomIsExplainedAsRunDesignExplainsIt) {
  const fs::path out = DesignTabDir("no_room");
  const fs::path scene = out / "cell.json";
  std::ofstream(scene) << R"({"obstacles": [{"name": "pillar", "type": "cylinder", "radius": 0.4, "length": 2,
                              "pose": [0, 0, 1, 0, 0, 0]}]})";
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.design\nclick limits.fill\nset design.scene " + scene.string() +
                     "\nset design.harmonics 2\nset design.f0 0.5\nset design.samples 40\n"
                     "click design.run\nwait design 300\n");
  EXPECT_FALSE(session.design_report().has_value());
  const DesignCommandReport direct = RunDesign(session.model(), session.design, session.limits, DesignControl{});
  ASSERT_EQ(direct.status(), DesignStatus::kNoRoom) << direct.BriefReport();
  EXPECT_NE(direct.result.infeasibility.explanation.find("pillar"), std::string::npos);
  EXPECT_EQ(session.last_error(), "design failed: " + direct.result.infeasibility.explanation);
  if (!HasFailure()) fs::remove_all(out);
}

// A motor limit set through the Design tab (a limits file's "actuators" and
// the transmission they act through, as `idbench design --limits
// --transmission`): the joint limits fill the table, the design equals
// RunDesign's on the same options (the command line's call, which reads the
// file itself), and its check holds the motor within its limit.
TEST(DesignTabTest, AMotorLimitThroughTheTransmissionEqualsRunDesign) {
  const fs::path out = DesignTabDir("motor");
  const fs::path transmission = out / "tx40.json";
  std::ofstream(transmission) << "{\"actuator_from_joint\": [[32,0,0,0,0,0], [0,32,0,0,0,0], [0,0,45,0,0,0], "
                                 "[0,0,0,-48,0,0], [0,0,0,0,45,0], [0,0,0,0,32,32]]}";
  const fs::path limits = out / "limits.json";
  constexpr double kMotorQdMax = 20.0;  // [rad/s] motor 6 (joints 5 and 6 through 32·(q̇5 + q̇6))
  WriteLimitsFile(limits, "{\"q_min\": -2.5, \"q_max\": 2.5, \"qd_max\": 3, \"qdd_max\": 20}",
                  "[{}, {}, {}, {}, {}, {\"qd_max\": " + std::to_string(kMotorQdMax) + "}]");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  // Without the transmission the motor limits are refused, naming the field.
  RunScript(gui, "click tab.design\nset design.limits " + limits.string() +
                     "\nset design.harmonics 2\nset design.f0 0.5\nset design.samples 40\n"
                     "set design.max_evaluations 20\nset design.clearance -1\nclick design.run\nframes 2\n");
  EXPECT_FALSE(session.design_report().has_value());
  EXPECT_EQ(session.last_error().rfind("design: transmission: ", 0), 0u) << session.last_error();
  // The file's joint limits are the table's.
  ASSERT_EQ(session.limits.size(), 6u);
  for (const JointLimits& l : session.limits) {
    EXPECT_EQ(l.q_min, -2.5);
    EXPECT_EQ(l.qdd_max, 20.0);
  }
  // "urdf" for a built-in robot: no URDF transmission, named.
  RunScript(gui, "set design.transmission urdf\nclick design.run\nframes 2\n");
  EXPECT_FALSE(session.design_report().has_value());
  EXPECT_NE(session.last_error().find("robot"), std::string::npos) << session.last_error();

  RunScript(gui, "set design.transmission " + transmission.string() + "\nclick design.run\nwait design 300\n");
  ASSERT_TRUE(session.design_report().has_value()) << session.last_error();
  const DesignCommandReport& shown = *session.design_report();
  EXPECT_EQ(session.design.limits, limits.string());
  EXPECT_EQ(session.design.transmission, transmission.string());
  ASSERT_EQ(shown.actuators.motors.size(), 6u);
  EXPECT_EQ(shown.actuators.motors[5].qd_max, kMotorQdMax);
  EXPECT_EQ(shown.actuators.transmission.actuator_from_joint(5, 4), 32.0);

  // The command line's RunDesign, reading the limits file and the transmission itself.
  const DesignCommandReport direct = RunDesign(session.model(), session.design, nullptr, std::nullopt);
  EXPECT_EQ(shown.result.value, direct.result.value);
  EXPECT_EQ(shown.result.final.cond, direct.result.final.cond);
  EXPECT_EQ(shown.result.trajectory.q0(), direct.result.trajectory.q0());
  EXPECT_EQ(shown.result.trajectory.a(), direct.result.trajectory.a());
  EXPECT_EQ(shown.result.trajectory.b(), direct.result.trajectory.b());
  ASSERT_EQ(shown.result.check.margins.size(), direct.result.check.margins.size());
  int motor_margins = 0;
  double motor_peak = 0.0;
  for (size_t i = 0; i < shown.result.check.margins.size(); ++i) {
    const ConstraintMargin& m = shown.result.check.margins[i];
    EXPECT_EQ(m.margin, direct.result.check.margins[i].margin) << i;
    if (m.motor < 0) continue;
    ++motor_margins;
    EXPECT_EQ(m.motor, 5);
    EXPECT_EQ(m.limit, kMotorQdMax);
    EXPECT_LE(m.value, kMotorQdMax);
    motor_peak = m.value;
  }
  EXPECT_EQ(motor_margins, 1);
  std::printf("motor limit through the GUI: criterion %.17g (RunDesign %.17g), motor 6 peak %.4g of %.4g rad/s\n",
              shown.result.value, direct.result.value, motor_peak, kMotorQdMax);
  if (!HasFailure()) fs::remove_all(out);
}

// design.transmission "urdf": the robot URDF's ros_control transmissions (a
// reduction of 50 on each of paper6r's joints, added to its URDF) carry the
// limits file's motor limit, as `idbench design --transmission urdf` does.
TEST(DesignTabTest, AMotorLimitThroughTheUrdfTransmissionEqualsRunDesign) {
  const fs::path out = DesignTabDir("urdf_motor");
  const fs::path robot = out / "geared.urdf";
  std::ofstream(robot) << testing::GearedPaper6rUrdf({"50", "50", "50", "50", "50", "50"});
  const fs::path limits = out / "limits.json";
  WriteLimitsFile(limits, "{\"q_min\": -2.5, \"q_max\": 2.5, \"qd_max\": 2, \"qdd_max\": 10}",
                  "[{\"qd_max\": 30}, {}, {}, {}, {}, {}]");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = robot.string(), .out_dir = out.string()}});
  Session& session = gui.session();
  ASSERT_TRUE(session.robot_transmission().has_value()) << session.last_error();
  RunScript(gui, "click tab.design\nset design.limits " + limits.string() +
                     "\nset design.transmission urdf\nset design.harmonics 2\nset design.f0 0.5\n"
                     "set design.samples 40\nset design.max_evaluations 20\nset design.clearance -1\n"
                     "click design.run\nwait design 300\n");
  ASSERT_TRUE(session.design_report().has_value()) << session.last_error();
  const DesignCommandReport& shown = *session.design_report();
  ASSERT_EQ(shown.actuators.motors.size(), 6u);
  EXPECT_EQ(shown.actuators.motors[0].qd_max, 30.0);
  EXPECT_EQ(shown.actuators.transmission.actuator_from_joint, 50.0 * Eigen::MatrixXd::Identity(6, 6));
  const DesignCommandReport direct =
      RunDesign(session.model(), session.design, nullptr, idbench::LoadRobot(robot.string()).transmission);
  EXPECT_EQ(shown.result.value, direct.result.value);
  EXPECT_EQ(shown.result.trajectory.a(), direct.result.trajectory.a());
  EXPECT_EQ(shown.result.trajectory.b(), direct.result.trajectory.b());
  int motor_margins = 0;
  for (const ConstraintMargin& m : shown.result.check.margins) {
    if (m.motor < 0) continue;
    ++motor_margins;
    EXPECT_EQ(m.motor, 0);
    EXPECT_LE(m.value, 30.0);
    std::printf("motor 1 through the URDF's reduction 50: peak %.4g of 30 rad/s\n", m.value);
  }
  EXPECT_EQ(motor_margins, 1);
  if (!HasFailure()) fs::remove_all(out);
}

// The given logs (design --given) as a comma-separated field: split into
// DesignCommandOptions::given, and the design on top of them equals
// RunDesign's, with the predicted sigma of every base parameter.
TEST(DesignTabTest, GivenLogsEqualRunDesign) {
  const fs::path out = DesignTabDir("given");
  const RobotModel puma = MakePuma560();
  const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  const fs::path log = out / "recorded.csv";
  std::ofstream(log) << FormatJointLogCsv(
      testing::SyntheticJointLog(puma, *motion, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0)));
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.design\nset design.given " + log.string() + ",,\n");
  EXPECT_EQ(session.design.given, std::vector<std::string>{log.string()});
  RunScript(gui, "click limits.fill\nset design.harmonics 2\nset design.f0 0.5\nset design.samples 40\n"
                 "set design.max_evaluations 20\nset design.clearance -1\nclick design.run\nwait design 300\n");
  ASSERT_TRUE(session.design_report().has_value()) << session.last_error();
  const DesignCommandReport& shown = *session.design_report();
  ASSERT_EQ(shown.given.size(), 1u);
  const DesignCommandReport direct = RunDesign(session.model(), session.design, session.limits, DesignControl{});
  EXPECT_EQ(shown.result.value, direct.result.value);
  EXPECT_EQ(shown.sigma_with_new, direct.sigma_with_new);
  EXPECT_EQ(shown.sigma_given.size(), static_cast<Eigen::Index>(shown.parameter_names.size()));
  if (!HasFailure()) fs::remove_all(out);
}

}  // namespace
}  // namespace idbench::gui
