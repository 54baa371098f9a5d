// The GUI driven headless as a user would: click named widgets, set values,
// wait for jobs. Asserts the state behind the widgets against independent
// computations and that the screenshots show the robot and the plots.
#include "idbench/gui/headless_gui.h"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "idbench/excitation/builtin_motions.h"
#include "idbench/excitation/design_regressor.h"
#include "idbench/gui/gui_script.h"
#include "idbench/ident/joint_torque_regressor.h"
#include "idbench/logs/joint_log_csv_writer.h"
#include "idbench/workbench/commands/simulate_command.h"
#include "ident/synthetic_log.h"
#include "render/image_test_util.h"
#include "workbench/gui/gui_test_util.h"
#include "idbench/workbench/formats/trajectory_file.h"

namespace idbench::gui {
namespace {

namespace fs = std::filesystem;

fs::path HeadlessGuiDir(const std::string& name) { return gui::TempDir("gui_test", name); }

// Pixels inside a widget's rectangle whose colour is saturated (robot links,
// plot lines and bars; the GUI's chrome is grey and white).
long long SaturatedPixels(const Image& image, const WidgetRect& r) {
  const testing::PixelBox box = testing::RobotBox(image, static_cast<int>(r.x0), static_cast<int>(r.y0),
                                                  static_cast<int>(r.width()), static_cast<int>(r.height()));
  return box.count;
}

// A small design on paper6r, simulated, identified, compared with the
// paper's motion and exported: the issue's done-when path.
TEST(HeadlessGuiTest, DesignSimulateIdentifyCompareExport) {
  const fs::path out = HeadlessGuiDir("flow");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  ASSERT_EQ(session.model().name(), "paper6r");

  // paper6r's file has no limits: the design refuses, says why, and the
  // session stays usable.
  RunScript(gui, "click design.run\nwait design 60\n");
  EXPECT_FALSE(session.design_report().has_value());
  EXPECT_NE(session.last_error().find("design failed"), std::string::npos) << session.last_error();

  // Limits from the table (filled, then one edited), a small fast design.
  RunScript(gui, R"(
click limits.fill
set limits.2.qd_max 0.8
set design.harmonics 2
set design.f0 0.5
set design.samples 40
set design.max_evaluations 20
click design.run
wait design 120
)");
  ASSERT_TRUE(session.design_report().has_value()) << session.last_error();
  const DesignCommandReport& design = *session.design_report();
  const DesignResult& r = design.result;
  ASSERT_EQ(design.limits.size(), 6u);
  EXPECT_EQ(design.limits[1].qd_max, 0.8);
  EXPECT_EQ(design.limits[0].qd_max, 1.0);
  EXPECT_EQ(design.limits[3].q_max, 3.0);
  EXPECT_TRUE(r.check.feasible()) << r.check.Explain();
  EXPECT_DOUBLE_EQ(r.trajectory.duration(), 2.0);

  // The criterion (log cond W, the torque model's default) from an
  // independent SVD of the regressor on the design grid.
  DesignOptions grid;
  grid.f0 = 0.5;
  grid.samples = 40;
  const DesignRegressor regressor =
      DesignRegressor::JointTorque(session.model(), *ParseFrictionTerms(session.design.friction, nullptr));
  const Eigen::MatrixXd W = regressor.Stack(r.trajectory, DesignSampleTimes(grid));
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(W).singularValues();
  const double cond = s(0) / s(s.size() - 1);
  EXPECT_NEAR(r.final.cond / cond, 1.0, 1e-8);
  EXPECT_NEAR(r.value, std::log(cond), 1e-8);
  EXPECT_LT(r.value, r.initial_value);
  // The live curve: best values so far, never increasing, ending at the result.
  const std::vector<double> curve = session.DesignCurve();
  ASSERT_FALSE(curve.empty());
  for (size_t k = 1; k < curve.size(); ++k) EXPECT_LE(curve[k], curve[k - 1]);
  EXPECT_EQ(curve.back(), r.value);
  // The velocity limits hold on a fine grid, checked here independently.
  for (double t = 0.0; t <= r.trajectory.duration(); t += 1e-3) {
    const JointState x = r.trajectory.At(t);
    for (int j = 0; j < 6; ++j) ASSERT_LE(std::abs(x.qd[j]), design.limits[static_cast<size_t>(j)].qd_max + 1e-9);
  }
  // The viewport now plays the designed motion.
  EXPECT_EQ(session.motion, "designed");
  const Image design_shot = gui.Screenshot();
  gui.WriteScreenshot((out / "design_tab.png").string());  // to look at
  const WidgetEntry* viewport = gui.widgets().Find("viewport");
  ASSERT_NE(viewport, nullptr);
  EXPECT_GT(SaturatedPixels(design_shot, viewport->rect), 5000);
  const WidgetEntry* curve_plot = gui.widgets().Find("design.curve");
  ASSERT_NE(curve_plot, nullptr);
  EXPECT_GT(curve_plot->rect.width(), 300.0f);
  EXPECT_GT(SaturatedPixels(design_shot, curve_plot->rect), 50);

  // Simulate the designed motion with torque noise, identify (OLS).
  RunScript(gui, R"(
click tab.experiment
set experiment.tau_noise 0.05
click experiment.simulate
wait simulate 120
click experiment.identify
wait identify 120
)");
  ASSERT_TRUE(session.log().has_value()) << session.last_error();
  EXPECT_EQ(session.log()->n_samples(), 2000);  // 2 s at 1 kHz
  ASSERT_TRUE(session.identify_report().has_value()) << session.last_error();
  const std::vector<IdentifiedRow> rows = session.IdentifiedRows();
  ASSERT_FALSE(rows.empty());
  // The robot file is the truth of the simulation: every base parameter
  // within 6 σ of it, the well-determined ones (σ < 0.01 %) within 0.1 %.
  int well_determined = 0;
  const Eigen::VectorXd& sigma = session.identify_report()->identification.linear.sigma;
  for (size_t k = 0; k < rows.size(); ++k) {
    EXPECT_LE(std::abs(rows[k].identified - rows[k].model_value), 6.0 * sigma[static_cast<Eigen::Index>(k)] + 1e-9)
        << rows[k].name;
    if (rows[k].sigma_percent < 0.01) {
      ++well_determined;
      EXPECT_LT(std::abs(rows[k].relative_error), 1e-3) << rows[k].name;
    }
    EXPECT_EQ(rows[k].status, ClassifyParameter(rows[k].identified, sigma[static_cast<Eigen::Index>(k)]));
  }
  EXPECT_GT(well_determined, 5);
  // Link 1 turns about a fixed axis: its mass cannot affect any torque.
  const std::vector<std::string> unexcited = session.UnexcitedParameters();
  EXPECT_NE(std::find(unexcited.begin(), unexcited.end(), "B1.m"), unexcited.end());
  const Image experiment_shot = gui.Screenshot();
  gui.WriteScreenshot((out / "experiment_tab.png").string());
  const WidgetEntry* bars = gui.widgets().Find("experiment.bars");
  ASSERT_NE(bars, nullptr);
  EXPECT_GT(SaturatedPixels(experiment_shot, bars->rect), 50);

  // The per-body experiment along the same motion: every mass estimate
  // against the robot file's link mass; B1 turns about its own axis only, so
  // some of its parameters are not identifiable, with the reason.
  RunScript(gui, "set identify.model per-body\nclick experiment.per_body\nwait per-body 120\n");
  ASSERT_TRUE(session.per_body_result().has_value()) << session.last_error();
  const PerBodyIdentificationResult& per_body = *session.per_body_result();
  ASSERT_EQ(per_body.bodies.size(), 6u);
  int masses = 0;
  for (int i = 0; i < 6; ++i) {
    for (const ParameterResult& p : per_body.bodies[static_cast<size_t>(i)].parameters) {
      if (!p.identifiable) {
        EXPECT_FALSE(p.reason.empty());
        continue;
      }
      if (p.name.rfind("m", 0) == 0) {
        ++masses;
        EXPECT_NEAR(p.identified, session.model().link(i).inertia.mass, 1e-8 * session.model().link(i).inertia.mass)
            << per_body.bodies[static_cast<size_t>(i)].name << "." << p.name;
      }
    }
  }
  EXPECT_GT(masses, 10);
  const auto& b1 = per_body.bodies[0].parameters;
  EXPECT_TRUE(std::any_of(b1.begin(), b1.end(), [](const ParameterResult& p) { return !p.identifiable; }));
  EXPECT_GT(SaturatedPixels(gui.Screenshot(), gui.widgets().Find("experiment.per_body_bars")->rect), 50);

  // Compare with the paper's motion, which moves two joints only: rank
  // deficient for the joint-torque model.
  RunScript(gui, R"(
click tab.compare
set compare.samples 40
set compare.trials 2
click compare.run
wait compare 120
)");
  ASSERT_TRUE(session.compare_report().has_value()) << session.last_error();
  const CompareReport& compare = *session.compare_report();
  ASSERT_EQ(compare.motions.size(), 2u);
  EXPECT_EQ(compare.motions[1].name, "paper");
  EXPECT_TRUE(std::isfinite(compare.motions[0].designed.cond));
  EXPECT_LT(compare.motions[1].designed.rank, compare.motions[0].designed.rank);
  EXPECT_FALSE(std::isfinite(compare.motions[1].designed.cond));

  // Export; the trajectory file reads back to the same motion.
  RunScript(gui, R"(
click tab.export
click export.trajectory_json
click export.trajectory_csv
click export.urdf
click export.screenshot
click export.report
wait report 120
)");
  EXPECT_TRUE(fs::is_regular_file(out / "report.html"));
  EXPECT_TRUE(fs::is_regular_file(out / "report.pdf"));
  EXPECT_TRUE(fs::is_regular_file(out / "trajectory.csv"));
  EXPECT_TRUE(fs::is_regular_file(out / "screenshot.png"));
  EXPECT_NE(ReadFile(out / "identified.urdf").find("<robot"), std::string::npos);
  const auto back = ParseTrajectoryJson(ReadFile(out / "trajectory.json"), 6, "trajectory.json");
  for (double t : {0.0, 0.37, 1.5}) EXPECT_TRUE(back->At(t).q.isApprox(r.trajectory.At(t).q, 1e-12));
  EXPECT_EQ(session.last_error().find("export"), std::string::npos) << session.last_error();
  if (!HasFailure()) fs::remove_all(out);  // else kept to look at
}

// The Log tab on a file, as a user with a recorded log: the Experiment tab's
// simulated log dropped onto the window twice (fit and held-out), friction,
// time window and estimator set; the identification equals RunIdentify's on
// the same options (the command line's call), the torque plots are drawn,
// and a bad value is refused naming it, the option unchanged.
TEST(HeadlessGuiTest, LogTabIdentifiesAFileAsTheLibrary) {
  const fs::path out = HeadlessGuiDir("log");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click tab.experiment\nset experiment.duration 4\nclick experiment.simulate\nwait simulate 120\n");
  const std::string log = (out / "log.csv").string();
  ASSERT_TRUE(fs::is_regular_file(log)) << session.last_error();
  gui.app().DropFiles({log, log});
  EXPECT_EQ(session.identify.data, log);
  EXPECT_EQ(session.identify.validate, log);
  RunScript(gui, R"(
click tab.log
set log.friction viscous,coulomb
set log.time_window 0.5,3.5
set log.estimator wls
click log.identify
wait identify 300
frames 2
)");
  ASSERT_TRUE(session.identify_report().has_value()) << session.last_error();
  IdentifyOptions options;
  options.data = options.validate = log;
  options.friction = {"viscous", "coulomb"};
  options.time_window = {0.5, 3.5};
  options.estimator = TorqueEstimator::kWls;
  const IdentifyReport expected = RunIdentify(session.model(), options);
  const JointTorqueIdentification& id = session.identify_report()->identification;
  EXPECT_EQ(id.beta, expected.identification.beta);
  EXPECT_EQ(id.consistent.pi, expected.identification.consistent.pi);
  EXPECT_EQ(session.identify_report()->n_samples, expected.n_samples);
  ASSERT_TRUE(session.identify_report()->validation.has_value());
  EXPECT_EQ(session.identify_report()->validation->relative_error, expected.validation->relative_error);
  // Measured against predicted torque, fit and held out, drawn.
  ASSERT_TRUE(session.fit_torques().has_value());
  ASSERT_TRUE(session.held_out_torques().has_value());
  EXPECT_EQ(session.fit_torques()->measured.cols(), 6);
  const WidgetEntry* plot = gui.widgets().Find("log.plot.1");
  ASSERT_NE(plot, nullptr);
  EXPECT_GT(SaturatedPixels(gui.Screenshot(), plot->rect), 50);
  // The residuals measured − predicted instead (log.plot_residuals).
  RunScript(gui, "set log.plot_residuals true\nframes 2\n");
  plot = gui.widgets().Find("log.plot.1");
  ASSERT_NE(plot, nullptr);
  EXPECT_GT(SaturatedPixels(gui.Screenshot(), plot->rect), 50);
  // Refused values name what is wrong and leave the options as they were.
  std::string why;
  EXPECT_FALSE(gui.Set("log.friction", "viscous,sticky", &why));
  EXPECT_NE(why.find("sticky"), std::string::npos) << why;
  EXPECT_EQ(session.identify.friction, (std::vector<std::string>{"viscous", "coulomb"}));
  EXPECT_FALSE(gui.Set("log.time_window", "1", &why));
  EXPECT_EQ(session.identify.time_window, (std::vector<double>{0.5, 3.5}));
  if (!HasFailure()) fs::remove_all(out);
}

// The Log tab offers what `identify` offers beyond one open-loop log: with a
// closed-loop estimator picked (iv) the controller and reference fields
// appear, and the identification equals RunIdentify's with them (noise-free
// closed loop: the robot file's base parameters to 1e-9); "more logs" stacks
// further logs as several --data do, "torque held" reads held torques.
TEST(HeadlessGuiTest, LogTabOffersTheClosedLoopEstimatorsAndSeveralLogs) {
  const fs::path out = HeadlessGuiDir("closed_loop");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  const fs::path pid = out / "pid.json";
  std::ofstream(pid) << R"({"kp": [2000, 2000, 1000, 200, 200, 200], "kd": [40, 40, 20, 4, 4, 4], "ki": 50,
                           "feedforward": "model"})";
  SimulateOptions simulate;
  simulate.duration = 4.0;
  simulate.controller = pid.string();
  const std::string log = (out / "closed.csv").string(), second = (out / "second.csv").string();
  std::ofstream(log) << FormatJointLogCsv(SimulateClosedLoopLog(session.model(), simulate).log);
  simulate.duration = 3.0;
  std::ofstream(second) << FormatJointLogCsv(SimulateClosedLoopLog(session.model(), simulate).log);
  EXPECT_EQ(gui.widgets().Find("log.controller"), nullptr);
  RunScript(gui, "click tab.log\nset log.data " + log + "\nset log.estimator iv\nframes 1\nset log.controller " +
                     pid.string() + "\nset log.reference general\nclick log.identify\nwait identify 300\nframes 1\n");
  ASSERT_TRUE(session.identify_report().has_value()) << session.last_error();
  IdentifyOptions options;
  options.data = log;
  options.estimator = TorqueEstimator::kInstrumentalVariables;
  options.controller = pid.string();
  options.reference = "general";
  const IdentifyReport expected = RunIdentify(session.model(), options);
  const JointTorqueIdentification& id = session.identify_report()->identification;
  EXPECT_EQ(id.beta, expected.identification.beta);
  ASSERT_TRUE(session.identify_report()->closed_loop.has_value());
  EXPECT_TRUE(session.identify_report()->closed_loop->converged);
  EXPECT_LT((id.beta - id.beta_model).norm(), 1e-9 * id.beta_model.norm());

  RunScript(gui, "set log.estimator ols\nframes 1\nset log.more_data " + second +
                     "\nset log.torque_held true\nclick log.identify\nwait identify 300\nframes 1\n");
  ASSERT_TRUE(session.identify_report().has_value()) << session.last_error();
  EXPECT_EQ(gui.widgets().Find("log.controller"), nullptr);  // ols: no closed loop to re-simulate
  IdentifyOptions several;
  several.data = log;
  several.more_data = {second};
  several.format.torque_held = true;
  const IdentifyReport stacked = RunIdentify(session.model(), several);
  EXPECT_EQ(session.identify_report()->identification.beta, stacked.identification.beta);
  ASSERT_EQ(session.identify_report()->parts.size(), 2u);
  EXPECT_EQ(session.identify_report()->parts[1].path, second);
  if (!HasFailure()) fs::remove_all(out);
}

// A synthetic log of the session's robot: `seconds` at 100 Hz from t = 0.
std::string WriteSyntheticLog(const Session& session, const fs::path& path, double seconds) {
  const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", session.model().n_dof(), {.duration = seconds});
  const Eigen::Index n = static_cast<Eigen::Index>(std::lround(100 * seconds)) + 1;
  std::ofstream(path) << FormatJointLogCsv(
      idbench::testing::SyntheticJointLog(session.model(), *motion, Eigen::VectorXd::LinSpaced(n, 0.0, seconds)));
  return path.string();
}

// The Log tab offers Coulomb's sign near rest as identify does: the
// identification with "Fc V" and "Fc v" equals RunIdentify's with
// coulomb_min_speed and coulomb_smoothing, differs from the default's, and a
// negative speed is refused with the field named; the fields go with
// "coulomb" in the friction.
TEST(HeadlessGuiTest, LogTabOffersCoulombsSignNearRest) {
  const fs::path out = HeadlessGuiDir("coulomb");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  const std::string log = WriteSyntheticLog(session, out / "log.csv", 4.0);
  RunScript(gui, "click tab.log\nset log.data " + log + "\nframes 1\nset log.coulomb_min_speed 0.05\n"
                 "set log.coulomb_smoothing 0.02\nclick log.identify\nwait identify 300\nframes 1\n");
  ASSERT_TRUE(session.identify_report().has_value()) << session.last_error();
  IdentifyOptions options;
  options.data = log;
  options.coulomb_min_speed = 0.05;
  options.coulomb_smoothing = 0.02;
  const IdentifyReport expected = RunIdentify(session.model(), options);
  const Eigen::VectorXd beta = session.identify_report()->identification.beta;
  EXPECT_EQ(beta, expected.identification.beta);
  options.coulomb_min_speed = options.coulomb_smoothing = 0.0;
  EXPECT_GT((beta - RunIdentify(session.model(), options).identification.beta).norm(), 1e-6 * beta.norm());

  RunScript(gui, "set log.coulomb_min_speed -1\nclick log.identify\nwait identify 300\nframes 1\n");
  EXPECT_NE(session.last_error().find("coulomb_min_speed"), std::string::npos) << session.last_error();
  RunScript(gui, "set log.friction viscous,offset\nframes 1\n");
  EXPECT_EQ(gui.widgets().Find("log.coulomb_min_speed"), nullptr);
  if (!HasFailure()) fs::remove_all(out);
}

// Files dropped onto the window (script verbs drop / shift-drop): the URDF
// loads as the robot and fills both robot fields, a log fills log.data and
// its preview and plot, Shift sends the next to the held-out log, anything
// else is a message naming it; the recent files of log.data list them, newest
// first, and nothing is written to an imgui.ini.
TEST(HeadlessGuiTest, DroppedFilesFillTheLogTab) {
  const fs::path out = HeadlessGuiDir("drop");
  const bool ini_before = fs::exists("imgui.ini");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "puma560", .out_dir = out.string()}});
  Session& session = gui.session();
  const std::string urdf = std::string(IDBENCH_SOURCE_DIR) + "/engine/robots/paper6r.urdf";
  RunScript(gui, "click tab.log\ndrop " + urdf + "\n");
  EXPECT_EQ(session.robot_source(), urdf);
  ASSERT_EQ(session.model().n_dof(), 6);
  const std::string first = WriteSyntheticLog(session, out / "first run.csv", 3.0);  // a space in the name
  const std::string second = WriteSyntheticLog(session, out / "second.csv", 2.0);
  const std::string third = WriteSyntheticLog(session, out / "third.csv", 2.0);
  std::ofstream(out / "picture.png") << "not a log";
  RunScript(gui, "drop " + first + "\nshift-drop " + second + "\ndrop " + (out / "picture.png").string() + "\n");
  EXPECT_EQ(session.identify.data, first);
  EXPECT_EQ(session.identify.validate, second);
  EXPECT_NE(session.last_error().find("'picture.png'"), std::string::npos) << session.last_error();
  EXPECT_NE(session.last_error().find(".urdf"), std::string::npos) << session.last_error();
  // The preview of its first rows and the plot of the log are drawn.
  EXPECT_NE(gui.widgets().Find("log.preview"), nullptr);
  EXPECT_NE(gui.widgets().Find("log.overview"), nullptr);
  // Without Shift a log replaces the log; the recent files give the first back.
  gui.Drop({third});
  EXPECT_EQ(session.identify.data, third);
  RunScript(gui, "set log.data.recent 2\nframes 1\n");
  EXPECT_EQ(session.identify.data, first);
  std::string why;
  EXPECT_FALSE(gui.Set("log.data.recent", "3", &why));  // two files so far
  EXPECT_FALSE(gui.Set("log.validate.recent", "2", &why));
  RunScript(gui, "set log.validate.recent 1\nset log.robot.recent 1\nframes 2\n");
  EXPECT_EQ(session.identify.validate, second);
  EXPECT_EQ(session.robot_source(), urdf);
  EXPECT_EQ(fs::exists("imgui.ini"), ini_before);
  if (!HasFailure()) fs::remove_all(out);
}

// The KUKA LWR4+ URDF and a recorded log (../shared/data/kuka_lwr4, skipped
// when absent) dropped together: the robot loads, the log fills log.data, its
// preview and its plot; the second log dropped with Shift is the held-out one.
TEST(HeadlessGuiTest, DroppedKukaUrdfAndLogFillTheLogTab) {
  const fs::path data = fs::path(IDBENCH_SOURCE_DIR) / ".." / "shared" / "data" / "kuka_lwr4";
  if (!fs::exists(data / "logs" / "measurements_1.csv"))
    GTEST_SKIP() << "real-robot data not found at " << data.string()
                 << " (../shared/data/kuka_lwr4 beside the checkout; not part of the project)";
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = HeadlessGuiDir("kuka").string()}});
  Session& session = gui.session();
  const std::string urdf = (data / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string();
  const std::string fit = (data / "logs" / "measurements_1.csv").string();
  const std::string held_out = (data / "logs" / "measurements_3.csv").string();
  RunScript(gui, "click tab.log\n");
  gui.Drop({urdf, fit});
  RunScript(gui, "shift-drop " + held_out + "\nframes 2\n");
  EXPECT_EQ(session.robot_source(), urdf);
  EXPECT_EQ(session.model().n_dof(), 7);
  EXPECT_EQ(session.identify.data, fit);
  EXPECT_EQ(session.identify.validate, held_out);
  EXPECT_TRUE(session.last_error().empty()) << session.last_error();
  EXPECT_NE(gui.widgets().Find("log.preview"), nullptr);
  EXPECT_NE(gui.widgets().Find("log.overview"), nullptr);
}

// A drag across the log's plot (drag log.overview 0.2 0.7) chooses the time
// window at 20 % and 70 % of the log's span, draws it shaded, and identifies
// as the same window typed into log.time_window.
TEST(HeadlessGuiTest, DragOnTheLogPlotChoosesTheTimeWindow) {
  const fs::path out = HeadlessGuiDir("drag");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  const std::string log = WriteSyntheticLog(session, out / "run.csv", 4.0);  // t from 0 to 4 s
  RunScript(gui, "click tab.log\nset log.data " + log + "\nset log.friction viscous\nframes 2\n"
                 "drag log.overview 0.2 0.7\n");
  const std::vector<double> window = session.identify.time_window;
  ASSERT_EQ(window.size(), 2u);
  // The mouse sits on whole pixels (ImGui floors its position): the times at
  // those pixels, the plot's width spanning the log's 4 s.
  const WidgetEntry* plot = gui.widgets().Find("log.overview");
  ASSERT_NE(plot, nullptr);
  const double x0 = plot->rect.x0, width = plot->rect.width();
  EXPECT_NEAR(window[0], (std::floor(x0 + 0.2 * width) - x0) / width * 4.0, 1e-6);
  EXPECT_NEAR(window[1], (std::floor(x0 + 0.7 * width) - x0) / width * 4.0, 1e-6);
  EXPECT_NEAR(window[0], 0.8, 4.0 / width);  // within a pixel of 20 % and 70 %
  EXPECT_NEAR(window[1], 2.8, 4.0 / width);
  // Shaded between the two, not outside (bottom row of the plot, under the lines).
  const Image image = gui.Screenshot();
  auto blue = [&](double fraction) {
    const std::uint8_t* p = image.at(static_cast<int>(plot->rect.x0 + fraction * plot->rect.width()),
                                     static_cast<int>(plot->rect.y1) - 2);
    return p[2] > p[0] + 20;
  };
  EXPECT_TRUE(blue(0.3));
  EXPECT_TRUE(blue(0.6));
  EXPECT_FALSE(blue(0.1));
  EXPECT_FALSE(blue(0.9));

  RunScript(gui, "click log.identify\nwait identify 300\n");
  ASSERT_TRUE(session.identify_report().has_value()) << session.last_error();
  const Eigen::VectorXd dragged = session.identify_report()->identification.beta;
  const long long dragged_samples = session.identify_report()->n_samples;
  EXPECT_LE(dragged_samples, 201);  // at most 0.8 to 2.8 s of the 401 samples at 100 Hz
  EXPECT_GE(dragged_samples, 150);
  char typed[80];
  std::snprintf(typed, sizeof typed, "%.17g,%.17g", window[0], window[1]);
  RunScript(gui, std::string("set log.time_window ") + typed + "\nclick log.identify\nwait identify 300\n");
  ASSERT_TRUE(session.identify_report().has_value()) << session.last_error();
  EXPECT_EQ(session.identified_with().time_window, window);
  EXPECT_EQ(session.identify_report()->n_samples, dragged_samples);
  const Eigen::VectorXd typed_beta = session.identify_report()->identification.beta;
  ASSERT_EQ(typed_beta.size(), dragged.size());
  EXPECT_LE((typed_beta - dragged).norm(), 1e-12 * dragged.norm());
  // A click without a drag: the whole log again.
  RunScript(gui, "click tab.log.data\ndrag log.overview 0.5 0.5\n");
  EXPECT_TRUE(session.identify.time_window.empty());
  if (!HasFailure()) fs::remove_all(out);
}

// The log's plot of a motion faster than its buckets: joint 1 a sine of
// period 16 ms in a 40 s log at 1 kHz (buckets of 16 samples, the interval
// at which every 16th sample, the plot's points before LogEnvelope, shows a
// flat line), the other joints still at 0. The plot shows the whole swing:
// in a column of the plot, the band covers the plotted height (±0.5 rad,
// the log's range), where a line would cover a pixel or two.
TEST(HeadlessGuiTest, LogPlotShowsTheSwingOfAMotionFasterThanItsBuckets) {
  const fs::path out = HeadlessGuiDir("envelope");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  const Eigen::Index n = 40001;
  JointLog log;
  log.t = Eigen::VectorXd::LinSpaced(n, 0.0, 40.0);
  log.q = Eigen::MatrixXd::Zero(n, 6);
  for (Eigen::Index i = 0; i < n; ++i) log.q(i, 0) = 0.5 * std::sin(2 * M_PI * log.t[i] / 0.016 + 0.3);
  log.tau = Eigen::MatrixXd::Zero(n, 6);
  std::ofstream(out / "fast.csv") << FormatJointLogCsv(log);
  RunScript(gui, "click tab.log\nset log.data " + (out / "fast.csv").string() + "\nframes 2\n");
  const WidgetEntry* plot = gui.widgets().Find("log.overview");
  ASSERT_NE(plot, nullptr) << gui.session().last_error();
  const Image image = gui.Screenshot();
  // The plotted rows: 16 px under the top (the caption) to 4 px above the bottom.
  const int top = static_cast<int>(plot->rect.y0) + 16, bottom = static_cast<int>(plot->rect.y1) - 4;
  for (double fraction : {0.25, 0.5, 0.75}) {
    const int u = static_cast<int>(plot->rect.x0 + fraction * plot->rect.width());
    int drawn = 0;
    for (int v = top; v < bottom; ++v) {
      const std::uint8_t* p = image.at(u, v);
      drawn += std::max({std::abs(p[0] - 252), std::abs(p[1] - 252), std::abs(p[2] - 252)}) > 15;
    }
    EXPECT_GE(drawn, 0.9 * (bottom - top)) << "column at " << fraction << " of the plot";
    std::printf("log plot column at %.2f: %d of %d rows drawn\n", fraction, drawn, bottom - top);
  }
  if (!HasFailure()) fs::remove_all(out);
}

// Identify on a long log shows its progress while frames keep coming, and
// Cancel (log.cancel) ends it: a message says so and nothing is identified.
TEST(HeadlessGuiTest, LogTabIdentifyShowsProgressAndCancels) {
  const fs::path out = HeadlessGuiDir("cancel");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  // 100 s at 1 kHz: 13 streaming blocks per pass.
  const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 100.0});
  const std::string log = (out / "long.csv").string();
  std::ofstream(log) << FormatJointLogCsv(
      idbench::testing::SyntheticJointLog(session.model(), *motion, Eigen::VectorXd::LinSpaced(100001, 0.0, 100.0)));
  RunScript(gui, "click tab.log\nset log.data " + log + "\nclick log.identify\n");
  int frames = 0;
  while (session.identify_progress().fraction == 0.0 && session.running(JobKind::kIdentify) && frames < 100000) {
    gui.RenderFrame();
    ++frames;
  }
  ASSERT_TRUE(session.running(JobKind::kIdentify));
  EXPECT_GT(session.identify_progress().fraction, 0.0);
  EXPECT_LT(session.identify_progress().fraction, 1.0);
  EXPECT_NE(gui.widgets().Find("log.progress"), nullptr);
  RunScript(gui, "click log.cancel\nwait identify 120\n");
  EXPECT_FALSE(session.identify_report().has_value());
  ASSERT_FALSE(session.messages().empty());
  EXPECT_NE(session.messages().back().text.find("cancelled"), std::string::npos) << session.messages().back().text;
  EXPECT_TRUE(session.last_error().empty()) << session.last_error();
  fs::remove_all(out);
}

// A long design runs while frames keep coming, shows progress, and stops on
// the Stop button with the best feasible design so far.
TEST(HeadlessGuiTest, DesignRunsInTheBackgroundAndStops) {
  const fs::path out = HeadlessGuiDir("stop");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click limits.fill\nset design.harmonics 2\nset design.samples 40\n"
                 "set design.max_evaluations 1000000\nclick design.run\n");
  // Frames render while the job runs; the live curve fills.
  int frames = 0;
  while (session.DesignCurve().empty() && session.running(JobKind::kDesign) && frames < 100000) {
    gui.RenderFrame();
    ++frames;
  }
  ASSERT_TRUE(session.running(JobKind::kDesign));
  EXPECT_FALSE(session.DesignCurve().empty());
  RunScript(gui, "click design.stop\nwait design 60\n");
  ASSERT_TRUE(session.design_report().has_value()) << session.last_error();
  EXPECT_TRUE(session.design_report()->result.stopped);
  EXPECT_LT(session.design_report()->result.evaluations, 1000000);
  fs::remove_all(out);
}

// The viewport follows the timeline and draws the markers asked for.
TEST(HeadlessGuiTest, ViewportFollowsTheTimelineAndShowsFrames) {
  HeadlessGui gui({.width = 960, .height = 600, .session = {.robot = "paper6r", .out_dir = HeadlessGuiDir("view").string()}});
  RunScript(gui, "click tab.experiment\nset experiment.motion general\nset timeline.time 0\nframes 1\n");
  const WidgetRect r = gui.widgets().Find("viewport")->rect;
  const int x = static_cast<int>(r.x0), y = static_cast<int>(r.y0), w = static_cast<int>(r.width()),
            h = static_cast<int>(r.height());
  const Image at_0 = gui.Screenshot();
  RunScript(gui, "set timeline.time 3\nframes 1\n");
  EXPECT_DOUBLE_EQ(gui.app().time(), 3.0);
  const Image at_3 = gui.Screenshot();
  // The general motion moves every joint: the robot's silhouette changes.
  long long moved = 0;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      moved += testing::IsRobotPixel(at_0.at(x + u, y + v)) != testing::IsRobotPixel(at_3.at(x + u, y + v));
  EXPECT_GT(moved, 500);
  // Link frames and centre-of-mass crosses stick out of the links.
  RunScript(gui, "set view.frames true\nset view.com true\nframes 1\n");
  const Image marked = gui.Screenshot();
  long long changed = 0;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::uint8_t *a = at_3.at(x + u, y + v), *b = marked.at(x + u, y + v);
      changed += std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) > 60;
    }
  }
  EXPECT_GT(changed, 200);
  fs::remove_all(gui.session().out_dir);
}

// Issue 35 item 34: while the Log tab is open the 3D view replays the log
// being identified (the robot as logged, at the log plot's time cursor), not
// the session's motion; the robot combo shows a loaded URDF as such. Truth:
// the general motion the log was written from, at one of its sample times.
TEST(HeadlessGuiTest, ViewportReplaysTheLogOfTheLogTab) {
  const fs::path out = HeadlessGuiDir("replay");
  HeadlessGui gui({.width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  const std::string log = WriteSyntheticLog(session, out / "run.csv", 4.0);  // 401 samples, 0 to 4 s
  const std::unique_ptr<Trajectory> logged = MakeBuiltinMotion("general", 6, {.duration = 4.0});
  RunScript(gui, "click tab.experiment\nset experiment.motion paper\nframes 1\nclick tab.log\nset log.data " + log +
                     "\nframes 2\n");
  gui.app().WaitForLogPlot();
  RunScript(gui, "frames 1\nset timeline.time 1.37\nframes 2\n");
  EXPECT_DOUBLE_EQ(gui.app().time(), 1.37);
  const Eigen::VectorXd shown = gui.app().shown_q();
  const Eigen::VectorXd truth = logged->At(1.37).q;
  EXPECT_LE((shown - truth).cwiseAbs().maxCoeff(), 1e-9) << shown.transpose() << "\n" << truth.transpose();
  // Not the session's motion at that instant.
  EXPECT_GT((shown - session.current_motion()->At(1.37).q).cwiseAbs().maxCoeff(), 1e-3);
  // Between two samples: linear between them.
  RunScript(gui, "set timeline.time 2.005\nframes 1\n");
  const Eigen::VectorXd between = 0.5 * (logged->At(2.0).q + logged->At(2.01).q);
  EXPECT_LE((gui.app().shown_q() - between).cwiseAbs().maxCoeff(), 1e-9);
  // The timeline spans the log; another tab shows the motion again.
  RunScript(gui, "set timeline.time 99\nframes 1\n");
  EXPECT_DOUBLE_EQ(gui.app().time(), 4.0);
  RunScript(gui, "click tab.experiment\nframes 2\nset timeline.time 1.37\nframes 1\n");
  EXPECT_LE((gui.app().shown_q() - session.current_motion()->At(1.37).q).cwiseAbs().maxCoeff(), 1e-12);

  // A URDF loaded: the combo says so instead of the built-in it showed.
  EXPECT_EQ(gui.app().robot_combo(), "paper6r");
  const std::string urdf = (fs::path(IDBENCH_SOURCE_DIR) / "engine/robots/paper6r.urdf").string();
  RunScript(gui, "set robot.urdf " + urdf + "\nclick robot.load_urdf\nframes 2\n");
  EXPECT_EQ(session.robot_source(), urdf) << session.last_error();
  EXPECT_EQ(gui.app().robot_combo(), "(URDF file)");
  RunScript(gui, "set robot.builtin puma560\nclick robot.load_builtin\nframes 2\n");
  EXPECT_EQ(session.robot_source(), "puma560");
  EXPECT_EQ(gui.app().robot_combo(), "puma560");
  if (!HasFailure()) fs::remove_all(out);
}

// Issue 20: a design that is not usable (here: one evaluation per start, so
// no start improves on where it began) is never exported as a motion a robot
// would run; `idbench design` writes only design.json for it too.
TEST(HeadlessGuiTest, UnusableDesignIsNotExported) {
  const fs::path out = HeadlessGuiDir("unusable");
  HeadlessGui gui({.width = 800, .height = 600, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  RunScript(gui, "click limits.fill\nset design.harmonics 2\nset design.f0 0.5\nset design.samples 40\n"
                 "set design.max_evaluations 1\nclick design.run\nwait design 60\n");
  ASSERT_TRUE(session.design_report().has_value()) << session.last_error();
  const DesignResult& r = session.design_report()->result;
  ASSERT_FALSE(r.usable()) << "one evaluation per start should not improve: " << r.initial_value << " -> " << r.value;
  EXPECT_NE(session.last_error().find("not usable"), std::string::npos) << session.last_error();
  RunScript(gui, "click tab.export\nclick export.trajectory_json\nclick export.trajectory_csv\n");
  EXPECT_NE(session.last_error().find("export: the design is not usable"), std::string::npos) << session.last_error();
  EXPECT_FALSE(fs::exists(out / "trajectory.json"));
  EXPECT_FALSE(fs::exists(out / "trajectory.csv"));
  fs::remove_all(out);
}

TEST(HeadlessGuiTest, BadInputShowsAMessageAndKeepsTheSession) {
  const fs::path out = HeadlessGuiDir("bad");
  const fs::path garbage = out / "broken.urdf";
  std::ofstream(garbage) << "<robot name='x'><link name=";
  HeadlessGui gui({.width = 800, .height = 600, .session = {.robot = "paper6r", .out_dir = out.string()}});
  Session& session = gui.session();
  const std::string script = "set robot.urdf " + (out / "missing.urdf").string() + "\nclick robot.load_urdf\n";
  RunScript(gui, script);
  EXPECT_NE(session.last_error().find("missing.urdf"), std::string::npos) << session.last_error();
  EXPECT_EQ(session.model().name(), "paper6r");
  RunScript(gui, "set robot.urdf " + garbage.string() + "\nclick robot.load_urdf\n");
  EXPECT_NE(session.last_error().find("broken.urdf"), std::string::npos) << session.last_error();
  EXPECT_EQ(session.model().name(), "paper6r");

  // Limits that cannot hold a motion (q_min >= q_max).
  RunScript(gui, "click limits.fill\nset limits.1.q_min 1\nset limits.1.q_max 0.5\nclick design.run\nwait design 60\n");
  EXPECT_FALSE(session.design_report().has_value());
  EXPECT_NE(session.last_error().find("design failed"), std::string::npos) << session.last_error();
  // Identify before any log: a message, no job.
  RunScript(gui, "click tab.experiment\n");
  session.StartIdentify();
  EXPECT_NE(session.last_error().find("simulate first"), std::string::npos);

  // Script errors name the step.
  std::string why;
  EXPECT_FALSE(RunGuiScript(gui, ParseGuiScript("frames 1\nclick no.such.widget\n", "s"), "s", &why));
  EXPECT_EQ(why.rfind("s:2: no widget 'no.such.widget'", 0), 0u) << why;
  EXPECT_FALSE(RunGuiScript(gui, ParseGuiScript("set experiment.tau_noise abc\n", "s"), "s", &why));
  EXPECT_NE(why.find("expected a number, got 'abc'"), std::string::npos) << why;

  // Another robot still loads, and the screenshot shows it.
  RunScript(gui, "click tab.design\nset robot.builtin puma560\nclick robot.load_builtin\nset limits.6.qd_max 2.5\n");
  EXPECT_EQ(session.model().name(), "puma560");
  EXPECT_TRUE(std::isfinite(session.limits[0].q_max));  // puma560's file has limits
  EXPECT_EQ(session.limits[5].qd_max, 2.5);              // the new robot's table is the one edited
  const WidgetEntry* viewport = gui.widgets().Find("viewport");
  ASSERT_NE(viewport, nullptr);
  EXPECT_GT(SaturatedPixels(gui.Screenshot(), viewport->rect), 2000);
  fs::remove_all(out);
}

}  // namespace
}  // namespace idbench::gui
