// Identification through a transmission (issue 21): a 6-joint arm with a
// coupled wrist like the Stäubli TX40's (N = [32, 32, 45, −48, 45, 32],
// motor 6 turns with joint 5: θm6 = N6·(q5 + q6)), simulated noise-free on
// the joint side by idbench's inverse dynamics plus each motor's rotor
// inertia and friction entered through Aᵀ, then written on the motor side by
// the small independent writer below (the TX40's relations by hand, not
// Transmission). identify reads the motor-side log through the description's
// transmission and must recover the truth, and fit as the joint-side log does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "idbench/engine/puma560.h"
#include "idbench/engine/urdf.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/workbench/commands/identify_command.h"
#include "idbench/workbench/commands/simulate_command.h"
#include "ident/synthetic_log.h"
#include "workbench/commands/tx40_wrist.h"

namespace idbench {
namespace {

// The text of `key: value` in joint `name`'s entry of joints.yaml ("" when absent).
std::string YamlJointValue(const std::string& yaml, const std::string& name, const std::string& key) {
  const size_t entry = yaml.find("- name: \"" + name + "\"\n");
  if (entry == std::string::npos) return "";
  const size_t next = yaml.find("- name:", entry + 1);
  const size_t at = yaml.find("    " + key + ": ", entry);
  if (at == std::string::npos || at > next) return "";
  const size_t begin = at + 6 + key.size();
  return yaml.substr(begin, yaml.find('\n', begin) - begin);
}
// The text of joint `name`'s element in a URDF or MJCF text.
std::string JointElement(const std::string& xml, const std::string& name) {
  const size_t at = xml.find("<joint name=\"" + name + "\"");
  if (at == std::string::npos) return "";
  const size_t end = xml.find("</joint>", at), line_end = xml.find('\n', at);
  return xml.substr(at, (xml.compare(line_end - 2, 2, "/>") == 0 ? line_end : end) - at);
}

const double kOffset[6] = {0.0, -M_PI / 2, M_PI / 2, 0.0, 0.0, 0.0};  // q = A⁻¹θm + q0
// Per motor: rotor inertia [kg m²], viscous [N m s/rad], Coulomb [N m], on θm.
constexpr double kIa[6] = {3e-4, 2.5e-4, 1.2e-4, 4e-5, 3.5e-5, 3e-5};
constexpr double kFv[6] = {1.5e-3, 2e-3, 1e-3, 4e-4, 3e-4, 2.5e-4};
constexpr double kFc[6] = {0.05, 0.08, 0.04, 0.02, 0.015, 0.012};

using testing::kTx40Ratio;

class IdentifyTransmissionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("idbench_transmission_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    // The arm without joint-side friction: the motors' terms are the truth.
    std::vector<Link> links = MakePuma560().links();
    for (Link& link : links) link.dynamics = JointDynamics{};
    model_.emplace("tx40_like", links);
    const std::unique_ptr<Trajectory> motion = MakeBuiltinMotion("general", 6, {.duration = 20.0});
    log_ = testing::SyntheticJointLog(*model_, *motion, Eigen::VectorXd::LinSpaced(4001, 0.0, 20.0));
    for (Eigen::Index s = 0; s < log_.n_samples(); ++s) {
      const Eigen::VectorXd thd = testing::Tx40MotorRates(log_.qd.row(s).transpose());
      const Eigen::VectorXd thdd = testing::Tx40MotorRates(log_.qdd.row(s).transpose());
      Eigen::VectorXd tau_m(6);
      for (int k = 0; k < 6; ++k) {
        tau_m[k] = kIa[k] * thdd[k] + kFv[k] * thd[k] + kFc[k] * ((thd[k] > 0) - (thd[k] < 0));
      }
      log_.tau.row(s) += testing::Tx40JointFromMotorTorques(tau_m).transpose();
    }
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // t, qm1..6, qdm1..6, qdd1..6, taum1..6 and a description with A.
  std::string WriteMotorSideLog() const {
    std::FILE* f = std::fopen((dir_ / "motor.csv").c_str(), "w");
    std::fprintf(f, "t,qm1,qm2,qm3,qm4,qm5,qm6,qdm1,qdm2,qdm3,qdm4,qdm5,qdm6,qdd1,qdd2,qdd3,qdd4,qdd5,qdd6,"
                    "taum1,taum2,taum3,taum4,taum5,taum6\n");
    for (Eigen::Index s = 0; s < log_.n_samples(); ++s) {
      Eigen::VectorXd q_minus_offset(6);
      for (int j = 0; j < 6; ++j) q_minus_offset[j] = log_.q(s, j) - kOffset[j];
      const Eigen::VectorXd qm = testing::Tx40MotorRates(q_minus_offset), qdm = testing::Tx40MotorRates(log_.qd.row(s).transpose());
      const Eigen::VectorXd taum = testing::Tx40MotorFromJointTorques(log_.tau.row(s).transpose());
      std::fprintf(f, "%.17g", log_.t[s]);
      for (const Eigen::VectorXd* v : {&qm, &qdm}) {
        for (int j = 0; j < 6; ++j) std::fprintf(f, ",%.17g", (*v)[j]);
      }
      for (int j = 0; j < 6; ++j) std::fprintf(f, ",%.17g", log_.qdd(s, j));
      for (int j = 0; j < 6; ++j) std::fprintf(f, ",%.17g", taum[j]);
      std::fprintf(f, "\n");
    }
    std::fclose(f);
    std::ofstream(dir_ / "motor.json") << R"({"files": [{"path": "motor.csv"}], "transmission": {
      "actuator_from_joint": [[32, 0, 0, 0, 0, 0], [0, 32, 0, 0, 0, 0], [0, 0, 45, 0, 0, 0],
                              [0, 0, 0, -48, 0, 0], [0, 0, 0, 0, 45, 0], [0, 0, 0, 0, 32, 32]],
      "joint_offset": [0, -1.5707963267948966, 1.5707963267948966, 0, 0, 0]}})";
    return (dir_ / "motor.json").string();
  }
  std::string WriteJointSideLog() const {
    std::FILE* f = std::fopen((dir_ / "joint.csv").c_str(), "w");
    std::fprintf(f, "t,q1,q2,q3,q4,q5,q6,qd1,qd2,qd3,qd4,qd5,qd6,qdd1,qdd2,qdd3,qdd4,qdd5,qdd6,tau1,tau2,tau3,tau4,"
                    "tau5,tau6\n");
    for (Eigen::Index s = 0; s < log_.n_samples(); ++s) {
      std::fprintf(f, "%.17g", log_.t[s]);
      for (const Eigen::MatrixXd* m : {&log_.q, &log_.qd, &log_.qdd, &log_.tau}) {
        for (int j = 0; j < 6; ++j) std::fprintf(f, ",%.17g", (*m)(s, j));
      }
      std::fprintf(f, "\n");
    }
    std::fclose(f);
    return (dir_ / "joint.csv").string();
  }
  IdentifyOptions Options(const std::string& data) const {
    IdentifyOptions options;
    options.data = data;
    options.friction = {"viscous", "coulomb", "rotor"};
    options.friction_side = FrictionSide::kActuator;
    options.out_dir = (dir_ / "out").string();
    return options;
  }
  // The truth as standard parameters: the links', then per motor Fv, Fc, Ia.
  Eigen::VectorXd TruePi(const FrictionModel& friction) const {
    Eigen::VectorXd pi = StandardParameters(*model_, friction);
    const int o = kInertialParametersPerLink * 6;
    for (int k = 0; k < 6; ++k) pi.segment<3>(o + 3 * k) << kFv[k], kFc[k], kIa[k];
    return pi;
  }

  // joints.yaml, identified.json's "joints", identified.urdf and identified.xml
  // carry identified.json's joint_side values for joints 1-4 and no number for
  // the coupled wrist (joints 5, 6), with a comment naming the coupling.
  void ExpectExportsCarryJointSideValuesAndNoneForTheCoupledWrist(const IdentifyOptions& options,
                                                                  const IdentifyReport& report,
                                                                  const nlohmann::json& identified) const {
    const std::string yaml = FormatJointDynamicsYaml(*model_, options, report);
    const std::string urdf = FormatIdentifiedUrdf(*model_, options, report);
    const std::string mjcf = FormatIdentifiedMjcf(*model_, options, report);
    const RobotModel loaded = LoadUrdfString(urdf).model;
    for (int j = 0; j < 6; ++j) {
      const nlohmann::json& listed = identified["joints"][j];
      const std::string& name = model_->link(j).joint_name;
      if (j < 4) {
        for (const auto& [key, side] : {std::pair{"viscous", "Fv"}, {"coulomb", "Fc"}, {"rotor_inertia", "Ia"}}) {
          const double truth = identified["joint_side"][side][j].get<double>();
          EXPECT_NEAR(std::stod(YamlJointValue(yaml, name, key)), truth, 1e-12 * truth) << name << " " << key;
          EXPECT_NEAR(listed[key].get<double>(), truth, 1e-12 * truth) << name << " " << key;
        }
        const double Fv = identified["joint_side"]["Fv"][j].get<double>();
        const double Fc = identified["joint_side"]["Fc"][j].get<double>();
        EXPECT_NEAR(loaded.link(j).dynamics.viscous, Fv, 1e-12 * Fv) << name;
        EXPECT_NEAR(loaded.link(j).dynamics.coulomb, Fc, 1e-12 * Fc) << name;
        EXPECT_FALSE(listed.contains("coupled_motors")) << name;
        continue;
      }
      for (const char* key : {"viscous", "coulomb", "rotor_inertia"}) {
        EXPECT_EQ(YamlJointValue(yaml, name, key), "null") << name << " " << key;
        EXPECT_TRUE(listed[key].is_null()) << name << " " << key;
      }
      EXPECT_EQ(listed["coupled_motors"], (j == 4 ? nlohmann::json{5, 6} : nlohmann::json{6})) << name;
      const std::string note = "joint '" + name + "' is coupled: " + (j == 4 ? "motors 5 and 6 turn" : "motor 6 turns");
      EXPECT_NE(yaml.find("    # " + note + " with it"), std::string::npos) << yaml;
      EXPECT_NE(urdf.find("<!-- " + note), std::string::npos) << urdf;
      EXPECT_NE(mjcf.find("<!-- " + note), std::string::npos) << mjcf;
      EXPECT_EQ(JointElement(urdf, name).find("<dynamics"), std::string::npos) << JointElement(urdf, name);
      const std::string mjcf_joint = JointElement(mjcf, name);
      ASSERT_FALSE(mjcf_joint.empty()) << name;
      for (const char* zero : {"armature=", "damping=", "frictionloss="}) {
        EXPECT_EQ(mjcf_joint.find(zero), std::string::npos) << mjcf_joint;
      }
    }
  }

  std::filesystem::path dir_;
  std::optional<RobotModel> model_;
  JointLog log_;
};

TEST_F(IdentifyTransmissionTest, MotorSideLogIdentifiesToTheTruthAndFitsAsTheJointSideLog) {
  const IdentifyOptions motor = Options(WriteMotorSideLog());
  const IdentifyReport from_motor = RunIdentify(*model_, motor);
  const JointTorqueIdentification& id = from_motor.identification;
  const Eigen::VectorXd beta_true = id.base.combination * TruePi(motor.friction_model());
  const double beta_error = (id.beta - beta_true).cwiseAbs().maxCoeff() / beta_true.cwiseAbs().maxCoeff();
  std::printf("motor-side log: max |β − β_true| / max |β_true| = %.3g, fit relative error %.3g\n", beta_error,
              id.fit.relative_error);
  EXPECT_LT(beta_error, 1e-8);
  EXPECT_LT(id.fit.relative_error, 1e-8);
  // Each motor's viscous and Coulomb friction is a base parameter of its own.
  for (int k = 1; k <= 6; ++k) {
    for (const char* term : {"Fvm", "Fcm"}) {
      const std::string name = term + std::to_string(k);
      const auto at = std::find(id.base.names.begin(), id.base.names.end(), name);
      ASSERT_NE(at, id.base.names.end()) << name;
      const double truth = term[1] == 'v' ? kFv[k - 1] : kFc[k - 1];
      EXPECT_NEAR(id.beta[at - id.base.names.begin()], truth, 1e-8 * truth) << name;
    }
  }

  // Each motor's rotor inertia where the arm's geometry separates it from the links'.
  for (size_t b = 0; b < id.base.names.size(); ++b) {
    if (id.base.names[b].rfind("Iam", 0) == 0) std::printf("  base parameter %s = %.9g\n", id.base.names[b].c_str(), id.beta[b]);
  }
  // Friction on the joint side cannot model the coupled motor: the fit is
  // clearly worse on the same log.
  IdentifyOptions joint_friction = motor;
  joint_friction.friction_side = FrictionSide::kJoint;
  const double joint_side_error = RunIdentify(*model_, joint_friction).identification.fit.relative_error;
  std::printf("motor-side log, friction on the joints: fit relative error %.3g\n", joint_side_error);
  EXPECT_GT(joint_side_error, 1e-4);

  // The joint-side log, with the same transmission given as a URDF would.
  IdentifyOptions joint = Options(WriteJointSideLog());
  joint.format.transmission = Transmission{};
  joint.format.transmission->actuator_from_joint = motor.friction_model().actuator_from_joint;
  const IdentifyReport from_joint = RunIdentify(*model_, joint);
  const double same = (from_joint.identification.beta - id.beta).cwiseAbs().maxCoeff() / beta_true.cwiseAbs().maxCoeff();
  std::printf("joint-side log: max |β_joint − β_motor| / max |β_true| = %.3g\n", same);
  EXPECT_LT(same, 1e-8);
  EXPECT_LT((from_joint.identification.fit.joint_rms - id.fit.joint_rms).norm(), 1e-8 * log_.tau.norm() / 100);

  // identified.json: joint-side equivalents for joints 1-4, null for the coupled wrist.
  const nlohmann::json out = nlohmann::json::parse(FormatIdentifiedJson(*model_, motor, from_motor));
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(out["joint_side"]["Fv"][j].get<double>(), kFv[j] * kTx40Ratio[j] * kTx40Ratio[j], 1e-3 * kFv[j] * kTx40Ratio[j] * kTx40Ratio[j]);
    EXPECT_NEAR(out["joint_side"]["Fc"][j].get<double>(), kFc[j] * std::abs(kTx40Ratio[j]), 1e-3 * kFc[j] * std::abs(kTx40Ratio[j]));
  }
  for (int j = 4; j < 6; ++j) {
    for (const char* key : {"Ia", "Fv", "Fc"}) EXPECT_TRUE(out["joint_side"][key][j].is_null()) << key << j;
  }
  ExpectExportsCarryJointSideValuesAndNoneForTheCoupledWrist(motor, from_motor, out);
}

// `simulate` with the same transmission (a file as a log description's) and
// motor truth: the written motor-side log holds θm, θ̇m as the TX40's
// relations by hand give them from the joint side, keeps virtual work, and
// identifies to the same truth.
TEST_F(IdentifyTransmissionTest, SimulatedMotorSideLogKeepsVirtualWorkAndIdentifiesToTheTruth) {
  std::ofstream(dir_ / "wrist.json") << R"({"actuator_from_joint": [[32, 0, 0, 0, 0, 0], [0, 32, 0, 0, 0, 0],
      [0, 0, 45, 0, 0, 0], [0, 0, 0, -48, 0, 0], [0, 0, 0, 0, 45, 0], [0, 0, 0, 0, 32, 32]],
      "joint_offset": [0, -1.5707963267948966, 1.5707963267948966, 0, 0, 0]})";
  SimulateOptions simulate;
  simulate.duration = 10.0;
  simulate.transmission = (dir_ / "wrist.json").string();
  simulate.motor_viscous.assign(std::begin(kFv), std::end(kFv));
  simulate.motor_coulomb.assign(std::begin(kFc), std::end(kFc));
  simulate.motor_rotor_inertia.assign(std::begin(kIa), std::end(kIa));
  const std::optional<Transmission> transmission = SimulateTransmission(simulate, 6, std::nullopt);
  ASSERT_TRUE(transmission.has_value());
  const MotorSideLog log = SimulateMotorSideLog(*model_, *transmission, simulate);
  std::ofstream(dir_ / "sim.csv") << FormatMotorSideLogCsv(log);
  std::ofstream(dir_ / "sim.json") << FormatMotorSideLogDescription(log, "sim.csv");

  // The written file, parsed here: t, qm1..6, qdm1..6, qdd1..6, taum1..6.
  std::ifstream csv(dir_ / "sim.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.substr(0, 13), "t,qm1,qm2,qm3");
  EXPECT_NE(line.find(",qdm6,qdd1,"), std::string::npos) << line;
  EXPECT_NE(line.find(",taum6"), std::string::npos) << line;
  const JointLog& joint = log.joint;
  double worst_work = 0.0, worst_rates = 0.0, worst_torque = 0.0;
  int s = 0;
  for (; std::getline(csv, line); ++s) {
    std::vector<double> v;
    for (size_t at = 0; at <= line.size();) {
      const size_t end = std::min(line.find(',', at), line.size());
      v.push_back(std::stod(line.substr(at, end - at)));
      at = end + 1;
    }
    ASSERT_EQ(v.size(), 25u);
    const Eigen::Map<const Eigen::VectorXd> qm(&v[1], 6), qdm(&v[7], 6), taum(&v[19], 6);
    const Eigen::VectorXd qd = joint.qd.row(s).transpose(), tau = joint.tau.row(s).transpose();
    Eigen::VectorXd q_minus_offset(6);
    for (int j = 0; j < 6; ++j) q_minus_offset[j] = joint.q(s, j) - kOffset[j];
    worst_rates = std::max({worst_rates, (qdm - testing::Tx40MotorRates(qd)).norm() / testing::Tx40MotorRates(qd).norm(),
                            (qm - testing::Tx40MotorRates(q_minus_offset)).norm() / testing::Tx40MotorRates(q_minus_offset).norm()});
    worst_torque = std::max(worst_torque, (testing::Tx40JointFromMotorTorques(taum) - tau).norm() / tau.norm());
    worst_work = std::max(worst_work, std::abs(tau.dot(qd) - taum.dot(qdm)) / (tau.norm() * qd.norm()));
  }
  EXPECT_EQ(s, joint.n_samples());
  std::printf("simulated motor-side log: %d samples; worst relative |τᵀq̇ − τmᵀθ̇m| = %.3g, θm/θ̇m vs A·q %.3g, "
              "Aᵀτm vs τ %.3g\n", s, worst_work, worst_rates, worst_torque);
  EXPECT_LT(worst_work, 1e-12);
  EXPECT_LT(worst_rates, 1e-12);
  EXPECT_LT(worst_torque, 1e-12);

  // Identified from the written log through its description.
  const IdentifyOptions motor = Options((dir_ / "sim.json").string());
  const IdentifyReport report = RunIdentify(*model_, motor);
  const JointTorqueIdentification& id = report.identification;
  const Eigen::VectorXd beta_true = id.base.combination * TruePi(motor.friction_model());
  const double beta_error = (id.beta - beta_true).cwiseAbs().maxCoeff() / beta_true.cwiseAbs().maxCoeff();
  std::printf("simulated motor-side log identified: max |β − β_true| / max |β_true| = %.3g, fit relative error %.3g\n",
              beta_error, id.fit.relative_error);
  EXPECT_LT(beta_error, 1e-9);
}

TEST_F(IdentifyTransmissionTest, ActuatorSideFrictionNeedsATransmission) {
  IdentifyOptions options = Options(WriteJointSideLog());
  try {
    RunIdentify(*model_, options);
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("friction_side \"actuator\": no transmission"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace idbench
