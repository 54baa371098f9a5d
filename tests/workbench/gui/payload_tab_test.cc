// The Payload tab driven headless as a user would: a simulated log of the
// PUMA 560 carrying a known payload on its last link, scripted through the
// tab, gives RunPayload's numbers (the command line's call on the same
// options) and the payload the log was simulated with; the export writes the
// files `idbench payload` writes; a motion that leaves the payload's inertia
// unseen shows "not identifiable" in place of numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/gui/gui_script.h"
#include "idbench/gui/headless_gui.h"
#include "workbench/gui/gui_test_util.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "ident/single_joint_motion.h"
#include "ident/synthetic_log.h"

namespace idbench::gui {
namespace {

namespace fs = std::filesystem;

fs::path PayloadTabDir(const std::string& name) { return gui::TempDir("payload_tab_test", name); }

// The payload the logs are simulated with, on the PUMA's last link.
constexpr double kMass = 2.5;  // [kg]
const Eigen::Vector3d kCom(0.02, -0.03, 0.08);  // p_BoPcm_B [m]
Eigen::Matrix3d Inertia() {  // I_Pcm_B [kg m²]
  return (Eigen::Matrix3d() << 0.02, 0.001, -0.002, 0.001, 0.025, 0.0015, -0.002, 0.0015, 0.015).finished();
}

// A noise-free log of `motion` on the loaded PUMA, written as a CSV file.
std::string WriteLoadedLog(const fs::path& dir, const std::string& name, const Trajectory& motion) {
  const RobotModel loaded = testing::WithPayload(MakePuma560(), kMass, kCom, Inertia());
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0);
  const std::string path = (dir / name).string();
  std::ofstream(path) << FormatJointLogCsv(testing::SyntheticJointLog(loaded, motion, t));
  return path;
}

TEST(PayloadTabTest, EstimatesAsTheLibraryAndRecoversTheTruth) {
  const fs::path out = PayloadTabDir("good");
  const std::string log = WriteLoadedLog(out, "loaded.csv", *MakeBuiltinMotion("general", 6, {.duration = 10.0}));
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.payload\nset payload.robot puma560\nset payload.data " + log +
                     "\nset payload.link link6\nset payload.friction viscous,coulomb\nclick payload.run\n"
                     "wait payload 300\nframes 2\n");
  ASSERT_TRUE(session.payload_summary().has_value()) << session.last_error();
  const PayloadSummary& shown = *session.payload_summary();

  // The command line's call on the same options.
  PayloadOptions options;
  options.robot = "puma560";
  options.loaded_log = log;
  options.payload_link = "link6";
  options.friction = {"viscous", "coulomb"};
  options.out_dir = (out / "payload").string();
  options.command_line = "gui: Payload tab";
  const RobotModel puma = MakePuma560();
  const PayloadSummary direct = RunPayload(puma, options);
  ASSERT_TRUE(direct.good()) << direct.message;
  EXPECT_TRUE(shown.good()) << shown.message;
  const Eigen::Matrix<double, 10, 1> q_shown = PayloadQuantities(shown.estimate.body);
  const Eigen::Matrix<double, 10, 1> q_direct = PayloadQuantities(direct.estimate.body);
  EXPECT_LE((q_shown - q_direct).norm(), 1e-12 * q_direct.norm());
  EXPECT_LE((shown.estimate.sigma - direct.estimate.sigma).norm(), 1e-12 * direct.estimate.sigma.norm() + 1e-300);

  // The truth, noise-free: mass, COM in link6's frame, inertia about the COM.
  PayloadBody truth;
  truth.mass = kMass;
  truth.p_BoPcm_B = kCom;
  const Eigen::Matrix3d I = Inertia();
  truth.I_Pcm_B << I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2);
  const Eigen::Matrix<double, 10, 1> q_truth = PayloadQuantities(truth);
  EXPECT_LE((q_shown - q_truth).cwiseAbs().maxCoeff(), 1e-6) << q_shown.transpose() << "\n" << q_truth.transpose();
  std::printf("payload tab: |gui - RunPayload| %.3g, max |gui - truth| %.3g\n", (q_shown - q_direct).norm(),
              (q_shown - q_truth).cwiseAbs().maxCoeff());

  // The table shows numbers (the ones above) and each quantity's status.
  const std::vector<PayloadRow> rows = session.PayloadRows();
  ASSERT_EQ(rows.size(), 10u);
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(rows[static_cast<size_t>(k)].value, q_shown[k]);
    EXPECT_EQ(rows[static_cast<size_t>(k)].status, "determined") << rows[static_cast<size_t>(k)].name;
  }
  EXPECT_EQ(rows[0].name, "mass");
  EXPECT_EQ(rows[0].value_text, "2.5");
  ASSERT_NE(gui.widgets().Find("payload.verdict"), nullptr);
  EXPECT_TRUE(gui.widgets().Find("payload.verdict")->visible);

  // Export: the files `idbench payload` writes for the same options, byte for byte.
  RunScript(gui, "click payload.export\n");
  EXPECT_EQ(ReadFile(out / "payload" / "payload.json"), FormatPayloadJson(puma, options, direct));
  EXPECT_EQ(ReadFile(out / "payload" / "payload.urdf.xml"), FormatPayloadUrdf(puma, options, direct));
  EXPECT_EQ(session.last_error(), "");
  if (!HasFailure()) fs::remove_all(out);
}

// Issue 35 item 33: the tab reads its logs with the session's one set of
// log-reading options: the Log tab's drive gains turn currents into torques,
// and the Design tab's base pose mounts the robot, as `idbench payload
// --drive-gains --base-pose` does. Truth: the payload the logs (currents
// i = τ / k of the PUMA rolled 0.4 rad on its base) were simulated with.
TEST(PayloadTabTest, ReadsCurrentsOnTheMountedBaseWithTheSessionsOptions) {
  const fs::path out = PayloadTabDir("mounted");
  const BasePose pose{{0.1, -0.2, 0.3, 0.4, 0.0, 0.2}};
  const Eigen::VectorXd gains = (Eigen::VectorXd(6) << 2.0, 3.0, 1.5, 0.5, 0.25, 0.2).finished();
  const RobotModel loaded = MountRobot(testing::WithPayload(MakePuma560(), kMass, kCom, Inertia()), pose);
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0);
  JointLog log = testing::SyntheticJointLog(loaded, *MakeBuiltinMotion("general", 6, {.duration = 10.0}), t);
  log.tau = log.tau * gains.cwiseInverse().asDiagonal();  // currents [A]
  std::string csv = FormatJointLogCsv(log);
  const size_t header_end = csv.find('\n');
  for (size_t at = csv.find("tau"); at < header_end; at = csv.find("tau", at)) csv.replace(at, 3, "i");
  const std::string path = (out / "currents.csv").string();
  std::ofstream(path) << csv;

  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.design\nset design.base_pose 0.1,-0.2,0.3,0.4,0,0.2\nclick tab.log\n"
                 "set log.drive_gains 2,3,1.5,0.5,0.25,0.2\nclick tab.payload\nset payload.robot puma560\n"
                 "set payload.data " + path + "\nset payload.friction viscous,coulomb\nclick payload.run\n"
                 "wait payload 300\nframes 2\n");
  ASSERT_TRUE(session.payload_summary().has_value()) << session.last_error();
  const PayloadSummary& shown = *session.payload_summary();
  EXPECT_TRUE(shown.good()) << shown.message;
  EXPECT_NEAR(shown.estimate.body.mass, kMass, 1e-6);
  EXPECT_LE((shown.estimate.body.p_BoPcm_B - kCom).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(session.payload_estimated_with().base_pose.xyz_rpy, pose.xyz_rpy);
  EXPECT_EQ(session.payload_estimated_with().format.drive_gains, std::vector<double>(gains.data(), gains.data() + 6));
  if (!HasFailure()) fs::remove_all(out);
}

// Only the wrist's last joint turns: the motion does not determine the
// payload's inertia; the tab says so instead of numbers, and the export
// writes payload.json only, with an error saying why.
TEST(PayloadTabTest, UnidentifiableQuantitiesShowAsText) {
  const fs::path out = PayloadTabDir("unseen");
  const std::string log = WriteLoadedLog(
      out, "wrist.csv", testing::SingleJointMotion((Eigen::VectorXd(6) << 0.3, -0.6, 0.4, 0.5, 0.7, 0.0).finished(), 5, 10.0));
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.payload\nset payload.robot puma560\nset payload.data " + log +
                     "\nclick payload.run\nwait payload 300\nframes 2\n");
  ASSERT_TRUE(session.payload_summary().has_value()) << session.last_error();
  EXPECT_EQ(session.payload_summary()->status, PayloadStatus::kNotIdentifiable);
  int unseen = 0;
  for (const PayloadRow& row : session.PayloadRows()) {
    if (row.status != "not identifiable") continue;
    ++unseen;
    EXPECT_EQ(row.value_text, "not identifiable") << row.name;
    EXPECT_EQ(row.sigma_text, "-");
    EXPECT_TRUE(std::isnan(row.value));
    EXPECT_NE(row.reason.find("link 'link6'"), std::string::npos) << row.reason;
  }
  EXPECT_GT(unseen, 0);
  EXPECT_EQ(session.PayloadRows()[4].value_text, "not identifiable");  // Ixx
  RunScript(gui, "click payload.export\n");
  EXPECT_TRUE(fs::is_regular_file(out / "payload" / "payload.json"));
  EXPECT_FALSE(fs::exists(out / "payload" / "payload.urdf.xml"));
  EXPECT_NE(session.last_error().find("payload.urdf.xml not written: not identifiable"), std::string::npos)
      << session.last_error();
  // A link the robot lacks is refused by the combo, naming the choices.
  std::string why;
  EXPECT_FALSE(gui.Set("payload.link", "tool0", &why));
  EXPECT_NE(why.find("link6"), std::string::npos) << why;
  if (!HasFailure()) fs::remove_all(out);
}

}  // namespace
}  // namespace idbench::gui
