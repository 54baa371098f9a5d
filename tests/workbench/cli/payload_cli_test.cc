// idbench payload, run as a user would: an identified robot's URDF, a log
// with the payload and (optionally) an unloaded one; the written files and
// the exit codes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "idbench/engine/base_pose.h"
#include "idbench/engine/puma560.h"
#include "idbench/engine/urdf.h"
#include "idbench/excitation/builtin_motions.h"
#include "ident/single_joint_motion.h"
#include "ident/synthetic_log.h"
#include "workbench/cli/cli_fixture.h"
#include "workbench/cli/joint_log_writer.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::Result;
using testing::Slurp;

class PayloadCliTest : public testing::CliFixture {
 protected:
  const RobotModel puma_ = MakePuma560();
  const double mass_ = 2.5;                                     // [kg]
  const Eigen::Vector3d com_{0.02, -0.03, 0.08};                // [m], link6 frame
  const Eigen::Matrix3d inertia_ = (Eigen::Matrix3d() << 0.02, 1e-3, -5e-4, 1e-3, 0.025, 1.5e-3, -5e-4, 1.5e-3,
                                    0.015).finished();           // [kg m²] about the COM

  // `robot`'s URDF as identify would write it.
  fs::path WriteRobot(const std::string& name, const RobotModel& robot) {
    std::ofstream(dir_ / name) << WriteUrdf(robot);
    return dir_ / name;
  }
  // t, q, qd, qdd, tau of `robot` along `motion` (10 s at 100 Hz), with a header.
  fs::path WriteLog(const std::string& name, const RobotModel& robot, const Trajectory& motion) {
    const JointLog log = testing::SyntheticJointLog(robot, motion, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0));
    std::ofstream(dir_ / name) << testing::JointLogCsvText(log, {"t", "q", "qd", "qdd", "tau"}, true);
    return dir_ / name;
  }
  RobotModel Loaded() const { return testing::WithPayload(puma_, mass_, com_, inertia_); }
  nlohmann::json ReadJson(const fs::path& path) { return nlohmann::json::parse(Slurp(path)); }
};

// The payload of every quantity from payload.json to 1e-6, with σ.
void ExpectPayload(const nlohmann::json& j, double mass, const Eigen::Vector3d& com, const Eigen::Matrix3d& I) {
  EXPECT_NEAR(j["mass"].get<double>(), mass, 1e-6 * mass);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(j["com"][c].get<double>(), com[c], 1e-7);
  const double inertia[6] = {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(j["inertia"][k].get<double>(), inertia[k], 1e-8) << k;
  EXPECT_GE(j["sigma"]["mass"].get<double>(), 0.0);
  EXPECT_EQ(j["sigma"]["inertia"].size(), 6u);
}

// Noise-free loaded and unloaded logs of the general motion: exit 0,
// payload.json holds the payload, and payload.urdf.xml pasted into the
// robot's URDF loads to the loaded robot.
TEST_F(PayloadCliTest, TwoLogsWriteThePayloadAndAFragmentThatLoads) {
  const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  const fs::path robot = WriteRobot("robot.urdf", puma_);
  const fs::path loaded = WriteLog("loaded.csv", Loaded(), *motion);
  const fs::path unloaded = WriteLog("unloaded.csv", puma_, *motion);
  const Result r = Run("payload --robot " + robot.string() + " --data " + loaded.string() + " --unloaded " +
                       unloaded.string() + " --out " + (dir_ / "p").string());
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("Verdict: estimated"), std::string::npos) << r.out;
  const nlohmann::json j = ReadJson(dir_ / "p" / "payload.json");
  ExpectPayload(j, mass_, com_, inertia_);
  EXPECT_EQ(j["verdict"]["status"], "estimated");
  EXPECT_TRUE(j["not_identifiable"].empty());
  EXPECT_EQ(j["link"], "link6");
  // The fragment, pasted before </robot>, gives the loaded robot's last link.
  std::string urdf = WriteUrdf(puma_);
  urdf.insert(urdf.rfind("</robot>"), Slurp(dir_ / "p" / "payload.urdf.xml"));
  const RobotModel merged = LoadUrdfString(urdf).model;
  const LinkInertia& got = merged.links().back().inertia;
  const RobotModel loaded_robot = Loaded();  // held: a reference into a temporary would dangle
  const LinkInertia& want = loaded_robot.links().back().inertia;
  EXPECT_NEAR(got.mass, want.mass, 1e-6);
  EXPECT_LT((got.p_BoBcm_B - want.p_BoBcm_B).norm(), 1e-7);
  EXPECT_LT((got.I_Bcm_B - want.I_Bcm_B).norm(), 1e-8);
}

// One log: the robot file's model subtracted; the same payload.
TEST_F(PayloadCliTest, OneLogSubtractsTheRobotFile) {
  const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  const fs::path loaded = WriteLog("loaded.csv", Loaded(), *motion);
  const Result r = Run("payload --robot puma560 --data " + loaded.string() + " --link link6 --out " +
                       (dir_ / "p").string());
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = ReadJson(dir_ / "p" / "payload.json");
  ExpectPayload(j, mass_, com_, inertia_);
  EXPECT_TRUE(j["unloaded"].is_null());
  EXPECT_TRUE(fs::exists(dir_ / "p" / "payload.urdf.xml"));
}

// Issue 35 item 33: payload reads logs as identify does. A log of motor
// currents (i = τ/K, a header of i1..i6) with --drive-gains, and logs of a
// ceiling-mounted robot (gravity along the world's −z seen from its base)
// with --base-pose, give the payload to 1e-6; without --base-pose the
// ceiling's logs give a wrong one.
TEST_F(PayloadCliTest, CurrentLogsAndMountedRobotsAreReadAsIdentifyReadsThem) {
  const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0);
  const Eigen::VectorXd gains = (Eigen::VectorXd(6) << 31.5, 55.0, 28.0, 7.5, 6.2, 4.1).finished();
  const fs::path currents = dir_ / "currents.csv";
  std::ofstream(currents) << testing::JointLogCsvText(testing::SyntheticJointLog(Loaded(), *motion, t),
                                                      {"t", "q", "qd", "qdd", "i"}, true, gains);
  Result r = Run("payload --robot puma560 --data " + currents.string() +
                 " --drive-gains 31.5,55,28,7.5,6.2,4.1 --out " + (dir_ / "i").string());
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  ExpectPayload(ReadJson(dir_ / "i" / "payload.json"), mass_, com_, inertia_);

  const BasePose ceiling{{0.0, 0.0, 2.5, M_PI, 0.0, 0.0}};
  const fs::path mounted = dir_ / "ceiling.csv";
  std::ofstream(mounted) << testing::JointLogCsvText(testing::SyntheticJointLog(MountRobot(Loaded(), ceiling), *motion, t),
                                                     {"t", "q", "qd", "qdd", "tau"}, true);
  r = Run("payload --robot puma560 --data " + mounted.string() + " --base-pose 0,0,2.5,3.141592653589793,0,0 --out " +
          (dir_ / "c").string());
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = ReadJson(dir_ / "c" / "payload.json");
  ExpectPayload(j, mass_, com_, inertia_);
  EXPECT_NEAR(j["base_pose"][3].get<double>(), M_PI, 1e-15);
  r = Run("payload --robot puma560 --data " + mounted.string() + " --out " + (dir_ / "u").string());
  const double unmounted_mass = ReadJson(dir_ / "u" / "payload.json")["mass"].is_number()
                                    ? ReadJson(dir_ / "u" / "payload.json")["mass"].get<double>()
                                    : NAN;
  EXPECT_FALSE(std::abs(unmounted_mass - mass_) < 0.05 * mass_) << "mass " << unmounted_mass << " without --base-pose";
}

// Only joint 6 turns: Ixx, Ixy, Iyy are not identifiable: named with their
// reason in payload.json (null, not numbers), no fragment, exit 1.
TEST_F(PayloadCliTest, UnseenTermsAreNamedAndNothingIsFitToWrite) {
  const testing::SingleJointMotion motion((Eigen::VectorXd(6) << 0.3, -0.6, 0.4, 0.5, 0.7, 0.0).finished(), 5, 10.0);
  const fs::path loaded = WriteLog("loaded.csv", Loaded(), motion);
  const Result r = Run("payload --robot puma560 --data " + loaded.string() + " --write-unverified --out " +
                       (dir_ / "p").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("Ixx, Ixy and Iyy"), std::string::npos) << r.err;
  const nlohmann::json j = ReadJson(dir_ / "p" / "payload.json");
  std::vector<std::string> names;
  for (const auto& entry : j["not_identifiable"]) {
    names.push_back(entry["name"]);
    EXPECT_NE(entry["reason"].get<std::string>().find("does not determine"), std::string::npos);
  }
  EXPECT_EQ(names, (std::vector<std::string>{"Ixx", "Ixy", "Iyy"}));
  EXPECT_TRUE(j["inertia"][0].is_null());
  EXPECT_TRUE(j["inertia"][1].is_null());
  EXPECT_TRUE(j["inertia"][3].is_null());
  EXPECT_NEAR(j["mass"].get<double>(), mass_, 1e-6);
  EXPECT_EQ(j["verdict"]["status"], "not identifiable");
  EXPECT_FALSE(fs::exists(dir_ / "p" / "payload.urdf.xml"));
}

// A robot file with link 3's mass 10 % off and one log: not a physical
// payload, exit 1 and no fragment, unless --write-unverified (exit 0); the
// unloaded log of the same motion fixes it.
TEST_F(PayloadCliTest, AWrongRobotFileIsRefusedUnlessForcedOrCancelled) {
  std::vector<Link> links = puma_.links();
  links[2].inertia.mass *= 1.1;
  const fs::path wrong = WriteRobot("wrong.urdf", RobotModel("puma560", links, puma_.gravity_W()));
  const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  const fs::path loaded = WriteLog("loaded.csv", Loaded(), *motion);
  const std::string common = "payload --robot " + wrong.string() + " --data " + loaded.string();
  Result r = Run(common + " --out " + (dir_ / "a").string());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("--write-unverified"), std::string::npos) << r.err;
  EXPECT_EQ(ReadJson(dir_ / "a" / "payload.json")["verdict"]["status"], "not physical");
  EXPECT_FALSE(fs::exists(dir_ / "a" / "payload.urdf.xml"));
  r = Run(common + " --write-unverified --out " + (dir_ / "b").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "b" / "payload.urdf.xml"));
  const fs::path unloaded = WriteLog("unloaded.csv", puma_, *motion);
  r = Run(common + " --unloaded " + unloaded.string() + " --out " + (dir_ / "c").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectPayload(ReadJson(dir_ / "c" / "payload.json"), mass_, com_, inertia_);
}

// Wrong options or input: exit 2, a message naming the flag, nothing written.
TEST_F(PayloadCliTest, WrongOptionsExitTwoAndWriteNothing) {
  const auto motion = MakeBuiltinMotion("general", 6, {.duration = 10.0});
  const fs::path loaded = WriteLog("loaded.csv", Loaded(), *motion);
  const std::string out = " --out " + (dir_ / "p").string();
  Result r = Run("payload --robot puma560 --data " + loaded.string() + " --link tool0" + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--link: robot 'puma560' has no link 'tool0'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'link6'"), std::string::npos) << r.err;
  r = Run("payload --robot puma560 --data " + loaded.string() + " --unloaded " + loaded.string() + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--unloaded:"), std::string::npos) << r.err;
  // The same file spelled differently: compared by device and inode.
  const std::string spelled = (dir_ / "." / "loaded.csv").string();
  r = Run("payload --robot puma560 --data " + loaded.string() + " --unloaded " + spelled + out);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--unloaded: expected a log without the payload, got '" + spelled + "', the loaded log '" +
                       loaded.string() + "' again (the same file)"), std::string::npos) << r.err;
  r = Run("payload --robot puma560 --data " + loaded.string() + " --unloaded-time-window 0,1" + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--unloaded-time-window"), std::string::npos) << r.err;
  r = Run("payload --data " + loaded.string() + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--robot"), std::string::npos) << r.err;
  r = Run("payload --robot puma560 --data " + (dir_ / "missing.csv").string() + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.csv"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "p"));
}

}  // namespace
}  // namespace idbench
