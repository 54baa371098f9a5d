// idbench simulate / identify / montecarlo, run as a user would.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <vector>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "idbench/engine/puma560.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/engine/urdf.h"
#include "ident/offset_geometry.h"
#include "ident/synthetic_log.h"
#include "workbench/cli/cli_fixture.h"
#include "workbench/geared_paper6r.h"
#include "workbench/cli/joint_log_writer.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::Result;
using testing::Slurp;

class IdentifyCliTest : public testing::CliFixture {
 protected:
  // A noise-free 10 s puma560 experiment at 100 Hz (1000 samples).
  fs::path SimulatePuma(const std::string& name, const std::string& extra = "") {
    const fs::path log = dir_ / name;
    const Result r = Run("simulate --robot puma560 --duration 10 --rate 100 " + extra + " --out " + log.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return log;
  }
  nlohmann::json Json(const fs::path& path) { return nlohmann::json::parse(Slurp(path)); }

  // ‖β̂ − β_file‖/‖β_file‖ over the base parameters of identified.json.
  static double BaseError(const nlohmann::json& j) {
    double num = 0.0, den = 0.0;
    for (const auto& p : j["base_parameters"]) {
      const double truth = p["robot_file_value"], value = p["value"];
      num += (value - truth) * (value - truth);
      den += truth * truth;
    }
    return std::sqrt(num / den);
  }
};

// Bullet (an independent simulator) → CSV → OLS recovers the robot file's
// base parameters; the held-out motion (every velocity reversed) is predicted.
TEST_F(IdentifyCliTest, NoiseFreeSimulationRecoversTheBaseParameters) {
  const fs::path log = SimulatePuma("log.csv"), held = SimulatePuma("held.csv", "--trajectory general-reversed");
  const Result r = Run("identify --robot puma560 --data " + log.string() + " --validate " + held.string() +
                       " --out " + (dir_ / "id").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = Json(dir_ / "id" / "identified.json");
  EXPECT_EQ(j["base_parameters"].size(), 52u);  // 36 inertial + Fv, Fc of 6 joints + 4 rotor inertias
  EXPECT_LT(BaseError(j), 1e-8);
  for (const auto& p : j["base_parameters"]) {
    const double truth = p["robot_file_value"], value = p["value"];
    EXPECT_LE(std::abs(value - truth), 1e-8 * std::max(1.0, std::abs(truth))) << p["name"];
    // Noise-free: σ = 0, yet the variance inflation is a property of W alone.
    ASSERT_TRUE(p["variance_inflation"].is_number()) << p["name"];
    EXPECT_GE(p["variance_inflation"].get<double>(), 1.0 - 1e-9) << p["name"];
  }
  EXPECT_LT(j["validation"]["relative_error"].get<double>(), 1e-10);
  EXPECT_EQ(j["n_samples"].get<int>(), 1000);
}

// Each base parameter of identified.json carries its combination of standard
// parameters: with the robot file's standard parameters (puma560's known
// inertias, listed in the same file) it gives the base parameter's robot
// file value, and the noise-free estimate, to rounding; its first term is
// the parameter the printed name starts with, coefficient 1.
TEST_F(IdentifyCliTest, BaseParametersCarryTheirCombinationsOfStandardParameters) {
  const fs::path log = SimulatePuma("log.csv");
  ASSERT_EQ(Run("identify --robot puma560 --data " + log.string() + " --out " + (dir_ / "id").string()).exit_code, 0);
  const nlohmann::json j = Json(dir_ / "id" / "identified.json");
  std::map<std::string, double> theta;  // the robot file's standard parameters
  for (const auto& p : j["physically_consistent"]["standard_parameters"]) theta[p["name"]] = p["robot_file_value"];
  ASSERT_EQ(theta.size(), 6u * 10u + 6u * 3u);  // 10 per link; Fv, Fc, Ia per joint
  int n_combined = 0;
  for (const auto& p : j["base_parameters"]) {
    const auto& terms = p["combination"];
    ASSERT_FALSE(terms.empty());
    const std::string name = p["name"];
    EXPECT_EQ(name.rfind(terms[0]["parameter"].get<std::string>(), 0), 0u) << name;
    EXPECT_EQ(terms[0]["coefficient"].get<double>(), 1.0) << name;
    double beta = 0.0, scale = 0.0;
    for (const auto& t : terms) {
      ASSERT_EQ(theta.count(t["parameter"]), 1u) << t["parameter"];
      beta += t["coefficient"].get<double>() * theta[t["parameter"]];
      scale += std::abs(t["coefficient"].get<double>() * theta[t["parameter"]]);
    }
    n_combined += terms.size() > 1;
    EXPECT_NEAR(beta, p["robot_file_value"].get<double>(), 1e-12 * std::max(scale, 1.0)) << name;
    EXPECT_NEAR(beta, p["value"].get<double>(), 1e-8 * std::max(scale, 1.0)) << name;
  }
  EXPECT_GT(n_combined, 10);  // puma560's base parameters do combine standard ones
}

// TLS and IRLS (--estimator tls, irls) from the same noise-free Bullet log:
// the robot file's base parameters to rounding, each with its passes and
// verdict in the table and identified.json. With 5 % of the torque rows
// spiked by 50 N m, OLS moves and IRLS keeps to the truth.
TEST_F(IdentifyCliTest, TlsAndIrlsRecoverTheBaseParametersAndIrlsIgnoresSpikes) {
  const fs::path log = SimulatePuma("log.csv");
  for (const char* estimator : {"tls", "irls"}) {
    const fs::path out = dir_ / estimator;
    const Result r = Run("identify --robot puma560 --estimator " + std::string(estimator) + " --data " + log.string() +
                         " --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << estimator << ": " << r.err;
    const nlohmann::json j = Json(out / "identified.json");
    EXPECT_EQ(j["estimator"], estimator);
    EXPECT_LT(BaseError(j), 1e-9) << estimator;
    EXPECT_TRUE(j["solve"]["converged"].get<bool>()) << estimator;
    EXPECT_GE(j["solve"]["iterations"].get<int>(), 1);
    EXPECT_NE(r.out.find("estimator " + std::string(estimator) + ": "), std::string::npos) << r.out;
  }
  // The same log with every 20th sample's torques offset by 50 N m.
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);
  std::string text = line + "\n";
  std::vector<int> tau_columns;
  {
    std::stringstream header(line);
    std::string name;
    for (int c = 0; std::getline(header, name, ','); ++c) {
      if (name.rfind("tau", 0) == 0) tau_columns.push_back(c);
    }
  }
  ASSERT_EQ(tau_columns.size(), 6u) << line;
  for (int row = 0; std::getline(in, line); ++row) {
    std::stringstream fields(line);
    std::string field, joined;
    for (int c = 0; std::getline(fields, field, ','); ++c) {
      const bool spike = row % 20 == 7 && std::find(tau_columns.begin(), tau_columns.end(), c) != tau_columns.end();
      char value[40];
      std::snprintf(value, sizeof(value), "%.17g", spike ? std::stod(field) + 50.0 : 0.0);
      joined += (c ? "," : "") + (spike ? std::string(value) : field);
    }
    text += joined + "\n";
  }
  const fs::path spiked = dir_ / "spiked.csv";
  std::ofstream(spiked) << text;
  std::map<std::string, double> error;
  for (const char* estimator : {"ols", "irls"}) {
    const fs::path out = dir_ / (std::string("spiked_") + estimator);
    const Result r = Run("identify --robot puma560 --estimator " + std::string(estimator) + " --data " +
                         spiked.string() + " --out " + out.string());
    ASSERT_LE(r.exit_code, 1) << estimator << ": " << r.err;  // the pc fit of a spiked log may be refused
    error[estimator] = BaseError(Json(out / "identified.json"));
  }
  std::printf("5 %% spiked torques: base parameter error OLS %.3g, IRLS %.3g\n", error["ols"], error["irls"]);
  EXPECT_GT(error["ols"], 1e-3);
  EXPECT_LT(error["irls"], 1e-6);
}

// A log without qd, qdd (as from a real robot): they come from the filtered q,
// regressor and torques are filtered in parallel. Accuracy is then set by the
// filter, not by rounding.
TEST_F(IdentifyCliTest, LogWithoutDerivativesIsFilteredInParallel) {
  const fs::path log = dir_ / "raw.csv";
  ASSERT_EQ(Run("simulate --robot puma560 --duration 10 --rate 1000 --no-derivatives --out " + log.string()).exit_code, 0);
  EXPECT_EQ(Slurp(log).substr(0, Slurp(log).find('\n')), "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6");
  const Result r = Run("identify --robot puma560 --data " + log.string() + " --out " + (dir_ / "id").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = Json(dir_ / "id" / "identified.json");
  // Measured: 0.3 % torque error, 12 % base-parameter error (weakly excited
  // parameters absorb the filter's bias; 7.9 % with the pivot-chosen base set).
  EXPECT_LT(j["fit"]["relative_error"].get<double>(), 0.005);
  EXPECT_LT(BaseError(j), 0.15);
}

// identified.urdf holds the physically consistent estimate: loaded back as the
// robot, it predicts the torques the estimate predicts. (Fv, Fc only:
// URDF has no field for rotor inertia.)
TEST_F(IdentifyCliTest, IdentifiedUrdfLoadsBackAndReproducesTheEstimate) {
  const fs::path log = SimulatePuma("log.csv", "--tau-noise 0.5,0.5,0.5,0.05,0.05,0.05");
  ASSERT_EQ(Run("identify --robot puma560 --estimator pc --friction viscous,coulomb --data " + log.string() +
                " --out " + (dir_ / "a").string()).exit_code, 0);
  const fs::path urdf = dir_ / "a" / "identified.urdf";
  const Result r = Run("identify --robot " + urdf.string() + " --friction viscous,coulomb --data " + log.string() +
                       " --out " + (dir_ / "b").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json a = Json(dir_ / "a" / "identified.json"), b = Json(dir_ / "b" / "identified.json");
  // The reloaded robot's torques fit the log exactly as the estimate did (the
  // base-parameter sets may be chosen differently: compare torques).
  for (size_t j = 0; j < 6; ++j) {
    const double estimate = a["fit"]["joint_rms"][j], reloaded = b["robot_file_fit"]["joint_rms"][j];
    EXPECT_NEAR(reloaded, estimate, 1e-9 * estimate) << "joint " << j + 1;
  }
  // Every link of the estimate is a physical body.
  for (const auto& e : a["physically_consistent"]["min_pseudo_inertia_eigenvalue"]) EXPECT_GT(e.get<double>(), 0.0);
  EXPECT_LE(a["physically_consistent"]["cost"].get<double>(), 1.05 * a["physically_consistent"]["ols_cost"].get<double>());
}

// joints.yaml carries, per joint, what a controller loads next to the URDF:
// on a noise-free log the estimate's viscous and Coulomb friction are the
// PUMA's published values (Corke's mdl_puma560, the robot file), and the
// file agrees with identified.json; the plausible estimate's links report
// their masses inside their bounds.
TEST_F(IdentifyCliTest, JointsYamlHoldsTheEstimatedFriction) {
  const fs::path log = SimulatePuma("log.csv");
  const Result r = Run("identify --robot puma560 --estimator pc --data " + log.string() + " --out " + (dir_ / "id").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string yaml = Slurp(dir_ / "id" / "joints.yaml");
  EXPECT_NE(Slurp(dir_ / "id" / "identified.xml").find("frictionloss=\""), std::string::npos);  // the MJCF beside them
  const nlohmann::json j = Json(dir_ / "id" / "identified.json");
  std::map<std::string, double> file_value;
  for (const auto& p : j["physically_consistent"]["standard_parameters"]) file_value[p["name"]] = p["robot_file_value"];
  size_t at = 0;
  for (int joint = 1; joint <= 6; ++joint) {
    for (const char* term : {"viscous", "coulomb"}) {
      at = yaml.find(std::string(term) + ": ", at);
      ASSERT_NE(at, std::string::npos) << term << " of joint " << joint << " in\n" << yaml;
      const double value = std::stod(yaml.substr(at + std::string(term).size() + 2));
      const double truth = file_value[(term[0] == 'v' ? "Fv" : "Fc") + std::to_string(joint)];
      EXPECT_NEAR(value, truth, 1e-6 * std::max(1.0, truth)) << term << " of joint " << joint;
      ++at;
    }
  }
  EXPECT_NE(yaml.find("drive_gain: null"), std::string::npos);
  for (const auto& link : j["physically_consistent"]["links"]) {
    EXPECT_GE(link["mass"].get<double>(), link["mass_bounds"][0].get<double>() * (1 - 1e-9)) << link["name"];
    EXPECT_LE(link["mass"].get<double>(), link["mass_bounds"][1].get<double>() * (1 + 1e-9)) << link["name"];
  }
}

// Bounds of the physically consistent estimate that cannot be right are
// usage errors before anything runs (exit 2, one line naming the option,
// nothing written): the PUMA's moving links weigh 33.45 kg in its file (with
// link 1's 10 kg), so 0.5–1.5 × that (16.7–50.2 kg) cannot reach 200 kg ± 10 %.
TEST_F(IdentifyCliTest, ImpossiblePlausibilityBoundsAreUsageErrors) {
  const fs::path log = SimulatePuma("log.csv");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--total-mass 200", "--total-mass 200 kg"},
      {"--mass-range 2,3", "--mass-range"},
      {"--mass-range 0.5", "--mass-range"},
      {"--com-bound hull", "--com-bound"},
      {"--prior-weight -1", "--prior-weight"},
      {"--total-mass-tolerance 2", "--total-mass-tolerance"}};
  for (const auto& [option, expected] : cases) {
    const fs::path out = dir_ / "bad";
    const Result r = Run("identify --robot puma560 --data " + log.string() + " " + option + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << option << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << option;
  }
  // A total mass the links can reach is accepted and held, here above the
  // file's (the start is outside the bounds: phase I).
  const Result ok = Run("identify --robot puma560 --data " + log.string() + " --total-mass 40 --out " + (dir_ / "ok").string());
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  double total = 0.0;
  const nlohmann::json j = Json(dir_ / "ok" / "identified.json");
  for (const auto& link : j["physically_consistent"]["links"]) total += link["mass"].get<double>();
  EXPECT_EQ(j["physically_consistent"]["links"].size(), 6u);
  EXPECT_GE(total, 0.9 * 40 * (1 - 1e-9));
  EXPECT_LE(total, 1.1 * 40 * (1 + 1e-9));
}

// The issue's Monte-Carlo: torque noise σ 0.5 N m (joints 1–3), 0.05 (4–6),
// 1000 samples of a 10 s Fourier motion, 100 seeded draws.
TEST_F(IdentifyCliTest, MonteCarloSpreadAgreesWithThePredictedCovariance) {
  const Result r = Run("montecarlo --robot puma560 --trials 100 --seed 7 --out " + dir_.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mean |dbeta|/|beta|"), std::string::npos);
  const nlohmann::json j = Json(dir_ / "montecarlo.json");
  EXPECT_LT(j["worst_sigma_ratio_deviation"].get<double>(), 0.2);
  const double mean = j["mean_relative_error"], predicted = j["predicted_relative_error"];
  EXPECT_NEAR(mean, predicted, 0.2 * predicted);
  // Held-out error is noise plus estimation error: just above the noise floor.
  const double held = j["mean_held_out_relative_error"], floor = j["held_out_noise_floor"];
  EXPECT_GT(held, floor);
  EXPECT_LT(held, 1.1 * floor);
}

// Bad logs: one message naming file, line and column; exit 1; nothing written.
// The paper's motion for 2 s moves its joints in turn and does not excite
// every base parameter of paper6r: those get no value (null, "not
// identifiable"), the others are within 6 σ of the truth, and the physically
// consistent fit, started near the robot file in the unexcited directions,
// stays at the least-squares cost (it reached 1e26 N² m² before).
TEST_F(IdentifyCliTest, MotionThatDoesNotExciteEverythingNamesWhatItLeavesOut) {
  const fs::path log = dir_ / "paper.csv";
  ASSERT_EQ(Run("simulate --robot paper6r --trajectory paper --duration 2 --tau-noise 0.05 --seed 1 --out " +
                log.string()).exit_code, 0);
  const Result r = Run("identify --robot paper6r --data " + log.string() + " --out " + (dir_ / "id").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("does not determine every base parameter"), std::string::npos) << r.out;
  const nlohmann::json j = Json(dir_ / "id" / "identified.json");
  const int n_base = static_cast<int>(j["base_parameters"].size());
  EXPECT_LT(j["rank"].get<int>(), n_base);
  EXPECT_TRUE(j["cond"].is_null());
  int missing = 0;
  for (const auto& p : j["base_parameters"]) {
    if (p["status"] == "not identifiable") {
      ++missing;
      EXPECT_TRUE(p["value"].is_null()) << p["name"];
      EXPECT_TRUE(p["sigma"].is_null()) << p["name"];
      continue;
    }
    const double truth = p["robot_file_value"], value = p["value"], sigma = p["sigma"];
    EXPECT_LE(std::abs(value - truth), 6.0 * sigma + 1e-9) << p["name"];
  }
  EXPECT_GE(missing, n_base - j["rank"].get<int>());
  const auto& pc = j["physically_consistent"];
  EXPECT_LT(pc["cost"].get<double>(), 1.01 * pc["ols_cost"].get<double>());
  for (double e : pc["min_pseudo_inertia_eigenvalue"]) EXPECT_GT(e, 0.0);
}

TEST_F(IdentifyCliTest, BadLogsNameLineAndColumn) {
  const std::string good = Slurp(SimulatePuma("log.csv"));
  const std::string header = good.substr(0, good.find('\n'));
  const std::string line2 = good.substr(good.find('\n') + 1, good.find('\n', good.find('\n') + 1) - good.find('\n') - 1);
  struct Case {
    std::string name, text, expected;
  };
  std::string replaced = line2;
  replaced.replace(replaced.find(','), 1, ",nan,");  // one field too many, and a NaN
  const std::vector<Case> cases = {
      {"missing_column", "t,q1,q2,q3,q4,q5,tau1,tau2,tau3,tau4,tau5,tau6\n0,0,0,0,0,0,0,0,0,0,0,0\n", "missing column 'q6'"},
      {"unknown_column", header + ",temp\n" + line2 + ",1\n", "column 26 ('temp'): unknown column"},
      {"field_count", header + "\n" + line2 + "\n" + replaced + "\n", ":3: 26 fields, expected 25"},
      {"nan", header + "\n" + line2 + "\n" + "0.01,nan" + line2.substr(line2.find(',', 2)) + "\n", ":3: column 2 ('q1'): nan is not finite"},
      {"time", header + "\n" + line2 + "\n" + line2 + "\n", ":3: column 1 ('t'): time 0"},
      {"too_few", header + "\n" + line2 + "\n", "1 usable samples"},
      {"limits", header + "\n" + "0,3" + line2.substr(line2.find(',', 2)) + "\n", ":2: column 2 ('q1'): 3 rad is outside joint 1's limits"},
      {"empty", "", ":1: empty file"},
  };
  for (const Case& c : cases) {
    const fs::path path = dir_ / (c.name + ".csv");
    std::ofstream(path) << c.text;
    const fs::path out = dir_ / ("out_" + c.name);
    const Result r = Run("identify --robot puma560 --data " + path.string() + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 2) << c.name;  // the input is wrong
    EXPECT_NE(r.err.find(path.string()), std::string::npos) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  // Options: a usage error (exit 2) before any file is read.
  const Result fancy = Run("identify --robot puma560 --data x.csv --estimator fancy");
  EXPECT_EQ(fancy.exit_code, 2);
  EXPECT_NE(fancy.err.find("ols, wls, pc, tls, irls, iv or didim"), std::string::npos) << fancy.err;
  EXPECT_EQ(Run("identify --robot puma560 --data x.csv --friction sticky").exit_code, 2);
  EXPECT_EQ(Run("identify --robot puma560 --data x.csv --model per-body").exit_code, 2);
  const Result unknown = Run("identify --robot nosuch --data x.csv");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("robot 'nosuch'"), std::string::npos);
  EXPECT_EQ(Run("simulate --robot puma560 --rate 300 --out " + (dir_ / "x.csv").string()).exit_code, 2);
}


// ---- The three real-log shapes of issue 12, on small synthetic logs --------

// Noise-free logs of puma560 along the general motion, computed by inverse
// dynamics (rigid body + Fv, Fc, Ia: the robot file's values are the truth).
class RealLogCliTest : public IdentifyCliTest {
 protected:
  RobotModel model_ = MakePuma560();
  std::unique_ptr<Trajectory> motion_ = MakeBuiltinMotion("general", 6, {.duration = 10.0});

  // Writes the chosen signals of a log, one sample a line; "t" "q" "qd" "qdd"
  // "tau" "i" (tau / gains) or "x" (a column of 7s, as a controller's extra
  // signals), with a header when `header`.
  fs::path Write(const std::string& name, const JointLog& log, const std::vector<std::string>& signals, bool header,
                 const Eigen::VectorXd& gains = Eigen::VectorXd()) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << testing::JointLogCsvText(log, signals, header, gains);
    return path;
  }
};

// (a) The Panda's shape: header t, q, qd, tau at ≈1 kHz with steps 0.7–8.8 ms
// and a dropped sample. Resampled (one line says how), qdd from the filtered
// qd, parallel filtering. What limits the accuracy is the torque's steps: the
// ideal Coulomb friction of the PUMA (sign(qd), ±21 N m at joint 1) is
// interpolated across the step that straddles a velocity reversal (42 N m off
// at one grid sample, 0.41 N m RMS over the log, q and qd are within 2e-7).
// Measured: torque fit 0.51 %, base parameters 6.9 % (uniformly sampled: 5e-8
// and 6e-6; the q-only log of LogWithoutDerivativesIsFilteredInParallel:
// 0.3 % and 12 %).
TEST_F(RealLogCliTest, HeaderWithMeasuredVelocityAndJitteredTime) {
  const Eigen::VectorXd t = testing::JitteredTimes(10.0, 1e-3, 0.3, 97, 8.8, 4000, 12);
  const fs::path jittered = Write("panda.csv", testing::SyntheticJointLog(model_, *motion_, t), {"t", "q", "qd", "tau"}, true);
  const fs::path uniform = Write("uniform.csv", testing::SyntheticJointLog(model_, *motion_, Eigen::VectorXd::LinSpaced(10001, 0.0, 10.0)),
                                 {"t", "q", "qd", "tau"}, true);
  const Result r = Run("identify --robot puma560 --data " + jittered.string() + " --out " + (dir_ / "a").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("panda.csv: resampled " + std::to_string(t.size()) + " samples with steps 0.7"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("–8.8 ms onto a uniform 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("qd from the log (filtered), qdd from the filtered qd"), std::string::npos) << r.out;
  ASSERT_EQ(Run("identify --robot puma560 --data " + uniform.string() + " --out " + (dir_ / "u").string()).exit_code, 0);
  const nlohmann::json a = Json(dir_ / "a" / "identified.json"), u = Json(dir_ / "u" / "identified.json");
  std::printf("jittered: fit %.3g, base error %.3g; uniform: fit %.3g, base error %.3g\n",
              a["fit"]["relative_error"].get<double>(), BaseError(a), u["fit"]["relative_error"].get<double>(), BaseError(u));
  EXPECT_LT(a["fit"]["relative_error"].get<double>(), 0.01);
  EXPECT_LT(BaseError(a), 0.1);
  EXPECT_LT(u["fit"]["relative_error"].get<double>(), 1e-6);
  EXPECT_LT(BaseError(u), 1e-4);
  // The same file without resampling was refused before: the step check.
  EXPECT_EQ(a["log_preparation"].size(), 1u);
}

// (b) The UR10e's shape: no header; t, q, qd, the controller's target
// currents (skipped), motor currents, then target torques (ignored); about
// 100 Hz with jitter; drive gains known; the robot at rest with the drives
// off (currents 0) for a second at both ends, cut by --time-window. At 100 Hz
// the Coulomb steps (see (a)) weigh more: measured fit 1.6 %, base 12 %.
TEST_F(RealLogCliTest, HeaderlessCurrentsWithGainsAndTimeWindow) {
  const Eigen::VectorXd gains = (Eigen::VectorXd(6) << 31.5, 55.0, 28.0, 7.5, -6.2, 4.1).finished();
  const Eigen::VectorXd t = testing::JitteredTimes(12.0, 1e-2, 0.2, 0, 1.0, 300, 13);
  JointLog log = testing::SyntheticJointLog(model_, *motion_, (t.array() - 1.0).cwiseMax(0.0).cwiseMin(10.0).matrix());
  log.t = t;
  for (int k = 0; k < log.n_samples(); ++k) {
    if (t[k] < 1.0 || t[k] > 11.0) log.tau.row(k).setZero();  // drives off
  }
  const fs::path path = Write("ur.csv", log, {"t", "q", "qd", "x", "i", "x"}, false, gains);
  const std::string args = "identify --robot puma560 --data " + path.string() +
                           " --columns t,q1..q6,qd1..qd6,_,_,_,_,_,_,i1..i6 --drive-gains 31.5,55,28,7.5,-6.2,4.1";
  const Result r = Run(args + " --time-window 1.2,10.8 --out " + (dir_ / "b").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("ur.csv: tau = K·i from the motor currents"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ur.csv: time window 1.2–10.8 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("onto a uniform 10"), std::string::npos) << r.out;
  const nlohmann::json b = Json(dir_ / "b" / "identified.json");
  std::printf("header-less currents: fit %.3g, base error %.3g\n", b["fit"]["relative_error"].get<double>(), BaseError(b));
  EXPECT_LT(b["fit"]["relative_error"].get<double>(), 0.03);
  EXPECT_LT(BaseError(b), 0.2);
  // Without the window the drives-off seconds spoil the fit: no physical
  // robot explains them, so the physically consistent estimate is refused
  // (exit 1, identified.json only).
  const Result spoilt = Run(args + " --out " + (dir_ / "c").string());
  EXPECT_EQ(spoilt.exit_code, 1) << spoilt.err;
  EXPECT_FALSE(fs::exists(dir_ / "c" / "identified.urdf"));
  const nlohmann::json c = Json(dir_ / "c" / "identified.json");
  EXPECT_FALSE(c["verdict"]["fit_to_load"].get<bool>());
  EXPECT_TRUE(b["verdict"]["fit_to_load"].get<bool>());
  std::printf("without the window: fit %.3g, base error %.3g\n", c["fit"]["relative_error"].get<double>(), BaseError(c));
  EXPECT_GT(c["fit"]["relative_error"].get<double>(), 5.0 * b["fit"]["relative_error"].get<double>());
  // Currents without gains, a window outside the log, a gap: one message each, exit 2, nothing written.
  struct Case {
    std::string args, expected;
  };
  const std::vector<Case> cases = {
      {"--columns t,q1..q6,qd1..qd6,_,_,_,_,_,_,i1..i6", "but no tau: pass --drive-gains"},
      {"--columns t,q1..q6,qd1..qd6,_,_,_,_,_,_,i1..i6 --drive-gains 31.5,55,28,7.5,-6.2,4.1 --time-window 1,30",
       "--time-window 1,30 is not inside the log"},
      {"--columns t,q1..q6,qd1..qd6,_,_,_,_,_,_,i1..i6 --drive-gains 31.5,55,28,7.5,-6.2,4.1 --max-gap 0.012",
       "ur.csv:301: column 't': a gap of 19"},
  };
  for (const Case& c : cases) {
    const Result bad = Run("identify --robot puma560 --data " + path.string() + " " + c.args + " --out " + (dir_ / "bad").string());
    EXPECT_EQ(bad.exit_code, 2) << c.args;
    EXPECT_NE(bad.err.find(c.expected), std::string::npos) << bad.err;
    EXPECT_EQ(bad.err.find("error:"), bad.err.rfind("error:")) << "printed once: " << bad.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
  }
  // Options that cannot fit: usage errors before anything runs.
  for (const char* a : {"--columns t,q1..q6,i1..i6 --drive-gains 1,2", "--time-window 5,2", "--angle-unit grad",
                               "--columns t,q1..q9,tau1..tau6", "--max-gap -1"}) {
    const Result usage = Run("identify --robot puma560 --data " + path.string() + " " + a + " --out " + (dir_ / "bad").string());
    EXPECT_EQ(usage.exit_code, 2) << a << ": " << usage.err;
  }
}

// Joint 5's current logged as τ/6.2 read with the gain -6.2 (and joint 2's as
// τ/55 with -55): those torques turn around, and their viscous and Coulomb
// friction come out negative and "determined". A sign note under the table
// names each, and the negative drive gain behind it; the right gains print
// none.
TEST_F(RealLogCliTest, NegativeFrictionFromANegativeGainGetsASignNote) {
  const Eigen::VectorXd gains = (Eigen::VectorXd(6) << 31.5, 55.0, 28.0, 7.5, 6.2, 4.1).finished();
  const fs::path path = Write("currents.csv", testing::SyntheticJointLog(model_, *motion_, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0)),
                              {"t", "q", "qd", "qdd", "i"}, false, gains);
  const std::string args = "identify --robot puma560 --data " + path.string() + " --columns t,q1..q6,qd1..qd6,qdd1..qdd6,i1..i6";
  const Result right = Run(args + " --drive-gains 31.5,55,28,7.5,6.2,4.1 --out " + (dir_ / "a").string());
  ASSERT_EQ(right.exit_code, 0) << right.err;
  EXPECT_EQ(right.out.find("sign:"), std::string::npos) << right.out;
  const Result wrong = Run(args + " --drive-gains 31.5,-55,28,7.5,-6.2,4.1 --out " + (dir_ / "b").string());
  const nlohmann::json b = Json(dir_ / "b" / "identified.json");
  for (const char* name : {"Fv5", "Fc5", "Fv2", "Fc2"}) {
    double value = 0.0;
    std::string status;
    for (const auto& p : b["base_parameters"]) {
      if (p["name"] == name) value = p["value"], status = p["status"];
    }
    EXPECT_LT(value, 0.0) << name;
    EXPECT_EQ(status, "determined") << name;
    const std::string joint = std::string(name).substr(2);
    const std::string gain = joint == "5" ? "6.2" : "55";
    EXPECT_NE(wrong.out.find(std::string("sign: ") + name + " = "), std::string::npos) << wrong.out;
    EXPECT_NE(wrong.out.find("(the drive gain of joint " + joint + " is negative, -" + gain +
                             " N m/A: if its current is logged with the same sign as its torque, give " + gain + ")"),
              std::string::npos) << wrong.out;
  }
}

// (c) The KUKA LWR's shape: header t, q, qd, qdd, tau at 200 Hz: used as read,
// exact to rounding.
TEST_F(RealLogCliTest, FullDerivativesAt200Hz) {
  const JointLog log = testing::SyntheticJointLog(model_, *motion_, Eigen::VectorXd::LinSpaced(2001, 0.0, 10.0));
  const fs::path path = Write("kuka.csv", log, {"t", "q", "qd", "qdd", "tau"}, true);
  const Result r = Run("identify --robot puma560 --data " + path.string() + " --validate " + path.string() + " --out " +
                       (dir_ / "k").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json k = Json(dir_ / "k" / "identified.json");
  EXPECT_EQ(k["n_samples"].get<int>(), 2001);
  EXPECT_EQ(k["derivatives"], "from the log");
  EXPECT_LT(BaseError(k), 1e-8);
  EXPECT_LT(k["validation"]["relative_error"].get<double>(), 1e-10);
}

// ---- The verdict: a robot file whose shapes are offset from its inertials ----

// puma560 drawn as the TX40's MDH URDF is (links floating apart): each link
// a 10 cm cube 40 cm beside its centre of mass. The log: the true robot
// (puma560's inertials, Fv, Fc, Ia) along the general motion, 1001 samples
// at 100 Hz, 0.05 N m torque noise.
class OffsetGeometryCliTest : public RealLogCliTest {
 protected:
  RobotModel offset_ = testing::WithOffsetShapes(MakePuma560(), Eigen::Vector3d(0.4, 0.0, 0.0), 0.1);

  fs::path Urdf(const std::string& name, const RobotModel& model) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << WriteUrdf(model);
    return path;
  }
  fs::path TrueLog() {
    return Write("log.csv",
                 testing::WithTorqueNoise(testing::SyntheticJointLog(offset_, *motion_, Eigen::VectorXd::LinSpaced(1001, 0.0, 10.0)), 0.05, 3),
                 {"t", "q", "qd", "qdd", "tau"}, true);
  }
};

// On main 6ab1a0b each centre of mass was held in its cube and the pc fit
// pinned there. Now the load warns once per link with the distance (0.4 −
// 0.05 = 0.35 m), those bounds are dropped (said in identified.json), and the
// default pc fit is fit to load: its cost within 10 % of the OLS optimum,
// the URDF written. %sigma is relative to the value printed (the pc value),
// null where that value is within 3 sigma of zero.
TEST_F(OffsetGeometryCliTest, DefaultOptionsDropTheContradictoryBoundsAndTheFitIsFitToLoad) {
  const fs::path urdf = Urdf("offset.urdf", offset_), log = TrueLog();
  const Result r = Run("identify --robot " + urdf.string() + " --estimator pc --data " + log.string() + " --out " +
                       (dir_ / "a").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const Link& link : offset_.links()) {
    EXPECT_NE(r.err.find("link '" + link.name + "': its centre of mass (<inertial> origin) lies 0.35 m outside the box"),
              std::string::npos) << r.err;
  }
  EXPECT_NE(r.out.find("Verdict: fit to load"), std::string::npos) << r.out;
  const nlohmann::json j = Json(dir_ / "a" / "identified.json");
  EXPECT_TRUE(j["verdict"]["fit_to_load"].get<bool>());
  EXPECT_EQ(j["verdict"]["status"], "fit_to_load");
  const double cost = j["physically_consistent"]["cost"], ols = j["physically_consistent"]["ols_cost"];
  EXPECT_NEAR(j["verdict"]["cost_excess_percent"].get<double>(), 100.0 * (cost - ols) / ols, 1e-9);
  EXPECT_LT(j["verdict"]["cost_excess_percent"].get<double>(), 10.0);
  for (const auto& link : j["physically_consistent"]["links"]) {
    EXPECT_TRUE(link["com_box_B"].is_null());
    EXPECT_EQ(link["com_bound"].get<std::string>().rfind("none: the file's centre of mass", 0), 0u) << link;
    EXPECT_NEAR(link["com_outside_geometry"].get<double>(), 0.35, 1e-12);
  }
  EXPECT_TRUE(fs::exists(dir_ / "a" / "identified.urdf"));
  EXPECT_TRUE(fs::exists(dir_ / "a" / "joints.yaml"));
  int null_count = 0;
  for (const auto& p : j["base_parameters"]) {
    const double value = p["value"], sigma = p["sigma"];
    if (std::abs(value) > 3.0 * sigma) {
      EXPECT_NEAR(p["rel_sigma_percent"].get<double>(), 100.0 * sigma / std::abs(value), 1e-9 * 100.0 * sigma / std::abs(value)) << p["name"];
    } else {
      EXPECT_TRUE(p["rel_sigma_percent"].is_null()) << p;
      ++null_count;
    }
  }
  std::printf("cost excess %.3g %%, %d of %zu %%sigma null\n", j["verdict"]["cost_excess_percent"].get<double>(),
              null_count, j["base_parameters"].size());
}

// A file whose centres of mass sit in its cubes while the robot's (the log's)
// lie 40 cm beside them: the contradiction the load cannot see. The pc fit
// is pinned on the boxes far above the OLS optimum: exit 1, one message
// naming the links on their bounds and the fix, identified.json written with
// the verdict, no identified.urdf or joints.yaml, whatever the estimator.
// --com-bound none fits; --write-unverified writes the refused model (exit 0).
TEST_F(OffsetGeometryCliTest, FitPinnedOnContradictoryBoundsIsRefused) {
  const fs::path urdf = Urdf("boxed.urdf", testing::WithComAtShapes(offset_)), log = TrueLog();
  const std::string args = "identify --robot " + urdf.string() + " --data " + log.string();
  for (const char* estimator : {"pc", "ols"}) {
    const fs::path out = dir_ / estimator;
    const Result r = Run(args + " --estimator " + estimator + " --out " + out.string());
    EXPECT_EQ(r.exit_code, 1) << estimator << ": " << r.err;
    EXPECT_EQ(r.err.find("outside the box"), std::string::npos) << r.err;  // the file agrees with itself
    EXPECT_NE(r.err.find("error: the physically consistent estimate is not a robot model ("), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--com-bound none"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--write-unverified"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("plausibility."), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("error:"), r.err.rfind("error:")) << "one message: " << r.err;
    ASSERT_TRUE(fs::exists(out / "identified.json")) << estimator;
    EXPECT_FALSE(fs::exists(out / "identified.urdf")) << estimator;
    EXPECT_FALSE(fs::exists(out / "joints.yaml")) << estimator;
    EXPECT_FALSE(fs::exists(out / "identified.xml")) << estimator;
    const nlohmann::json j = Json(out / "identified.json");
    EXPECT_FALSE(j["verdict"]["fit_to_load"].get<bool>());
    EXPECT_FALSE(j["verdict"]["robot_model_written"].get<bool>());
    EXPECT_NE(j["verdict"]["status"], "fit_to_load");
    const double cost = j["physically_consistent"]["cost"], ols = j["physically_consistent"]["ols_cost"];
    EXPECT_NEAR(j["verdict"]["cost_excess_percent"].get<double>(), 100.0 * (cost - ols) / ols,
                1e-9 * j["verdict"]["cost_excess_percent"].get<double>());
    EXPECT_GT(j["verdict"]["cost_excess_percent"].get<double>(), 100.0);
    int com = 0;
    for (const auto& b : j["verdict"]["bounds_at_optimum"]) {
      if (b["quantity"].get<std::string>().rfind("com_", 0) != 0) continue;
      ++com;
      EXPECT_NE(r.err.find("link '" + b["link"].get<std::string>() + "'"), std::string::npos) << r.err;
    }
    EXPECT_GT(com, 0) << j["verdict"];
    if (std::string(estimator) == "pc") std::printf("refused: %s\n", r.err.c_str());
  }
  const Result none = Run(args + " --estimator pc --com-bound none --out " + (dir_ / "none").string());
  EXPECT_EQ(none.exit_code, 0) << none.err;
  EXPECT_TRUE(Json(dir_ / "none" / "identified.json")["verdict"]["fit_to_load"].get<bool>());
  EXPECT_TRUE(fs::exists(dir_ / "none" / "identified.urdf"));
  const Result accepted = Run(args + " --estimator pc --write-unverified --out " + (dir_ / "w").string());
  EXPECT_EQ(accepted.exit_code, 0) << accepted.err;
  EXPECT_NE(accepted.err.find("warning: the physically consistent estimate is not a robot model"), std::string::npos)
      << accepted.err;
  EXPECT_TRUE(fs::exists(dir_ / "w" / "identified.urdf"));
  EXPECT_TRUE(Json(dir_ / "w" / "identified.json")["verdict"]["robot_model_written"].get<bool>());
}

// Options of the verdict: a cost tolerance that is not a fraction >= 0 is a
// usage error naming the flag; so is --prior-weight 0 (main 6ab1a0b ran it
// and reported "infeasible … -nan"), which leaves what the log does not
// determine arbitrary. --mass-range 1,1 (main: "infeasible … least violation
// 0") and a tiny prior weight run and converge, the masses at the file's.
TEST_F(IdentifyCliTest, VerdictOptionsAndDegenerateBoundsInRange) {
  const fs::path log = SimulatePuma("log.csv", "--tau-noise 0.5,0.5,0.5,0.05,0.05,0.05");
  for (const char* option : {"--cost-tolerance -1", "--prior-weight 0"}) {
    const Result bad = Run("identify --robot puma560 --data " + log.string() + " " + option + " --out " + (dir_ / "bad").string());
    EXPECT_EQ(bad.exit_code, 2) << option;
    EXPECT_NE(bad.err.find(std::string(option).substr(0, std::string(option).find(' '))), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
  }
  for (const char* option : {"--prior-weight 1e-8", "--mass-range 1,1"}) {
    const fs::path out = dir_ / "ok";
    const Result r = Run("identify --robot puma560 --estimator pc --data " + log.string() + " " + option + " --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << option << ": " << r.err;
    const nlohmann::json j = Json(out / "identified.json");
    EXPECT_TRUE(j["physically_consistent"]["converged"].get<bool>()) << option;
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
    if (std::string(option) == "--mass-range 1,1") {
      for (const auto& link : j["physically_consistent"]["links"]) {
        const double m = link["mass"], file = link["robot_file_mass"];
        EXPECT_NEAR(m, file, 1e-6 * file) << link["name"];
      }
    }
  }
}

// A window's message says what is wrong with it: three values, a bound that
// is not a finite number, or the order (all "T0 < T1" before); a huge cost
// tolerance is shown as %g, not 301 digits. Exit 2, nothing written.
TEST_F(IdentifyCliTest, WindowAndToleranceMessagesSayWhatIsWrong) {
  const fs::path log = SimulatePuma("log.csv");
  const std::string common = "identify --robot puma560 --data " + log.string() + " --validate " + log.string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--validate-window 1,2,3", "--validate-window: expected two values T0,T1 [s], got 3 (1,2,3)"},
      {"--validate-window nan,1", "--validate-window: expected finite bounds T0,T1 [s] (a number of seconds each), got nan,1"},
      {"--time-window -inf,inf", "--time-window: expected finite bounds T0,T1 [s] (a number of seconds each), got -inf,inf"},
      {"--time-window 5,2", "--time-window: expected T0,T1 [s] with T0 < T1, got 5,2"},
      {"--cost-tolerance 1e300", "--cost-tolerance: expected a fraction from 0 to 1e6, got 1e+300\n"}};
  for (const auto& [option, expected] : cases) {
    const Result r = Run(common + " " + option + " --out " + (dir_ / "bad").string());
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << option << ": " << r.err;
    const size_t error = r.err.find("idbench: error: ");
    EXPECT_LT(r.err.find('\n', error) - error, 200u) << option << ": " << r.err;  // one line, no 301 digits
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
  }
}

// --coulomb-min-speed (identify, gains, payload: one flag helper): accepted,
// it reaches the fold (0 gives the default's estimate to the bit, 0.05 rad/s
// another Fc), and a negative or NaN speed is refused before anything runs,
// exit 2, naming the flag.
TEST_F(IdentifyCliTest, CoulombMinSpeedIsAcceptedAndBadSpeedsAreUsageErrors) {
  const fs::path log = SimulatePuma("log.csv");
  const std::string common = "identify --robot puma560 --data " + log.string();
  std::vector<nlohmann::json> fc;
  for (const std::string speed : {"", " --coulomb-min-speed 0", " --coulomb-min-speed 0.05"}) {
    const fs::path out = dir_ / ("id" + std::to_string(fc.size()));
    const Result r = Run(common + speed + " --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << speed << ": " << r.err;
    nlohmann::json values;
    const nlohmann::json j = Json(out / "identified.json");
    for (const auto& p : j["base_parameters"]) {
      if (p["name"].get<std::string>().rfind("Fc", 0) == 0) values.push_back(p["value"]);
    }
    ASSERT_EQ(values.size(), 6u) << speed;
    fc.push_back(values);
  }
  EXPECT_EQ(fc[1], fc[0]);
  EXPECT_NE(fc[2], fc[0]);
  const std::string log_args = " --data " + log.string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {common + " --coulomb-min-speed -0.01", "--coulomb-min-speed: expected >= 0 rad/s, got -0.01"},
      {common + " --coulomb-min-speed nan", "--coulomb-min-speed: expected >= 0 rad/s, got nan"},
      {common + " --coulomb-smoothing -1", "--coulomb-smoothing: expected >= 0 rad/s, got -1"},
      {"gains" + log_args + " --loaded " + log.string() + " --loaded-time-window 0,5 --payload-mass 1 "
       "--coulomb-min-speed -1", "--coulomb-min-speed: expected >= 0 rad/s, got -1"},
      {"payload --robot puma560" + log_args + " --coulomb-min-speed -1",
       "--coulomb-min-speed: expected >= 0 rad/s, got -1"}};
  for (const auto& [command, expected] : cases) {
    const Result r = Run(command + " --out " + (dir_ / "bad").string());
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
    EXPECT_NE(r.err.find("idbench: error: " + expected + "\n"), std::string::npos) << command << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad"));
  }
}

// Gear ratios beyond any drive (|N| > 1e4, as drive gains are bounded) are
// refused before anything runs, exit 2, naming where they were given: a
// URDF's <mechanicalReduction> of 1e77 (before: a segfault with
// --friction-side actuator) and a description's 1e5 (before: run, with the
// base set cut without a word).
TEST_F(IdentifyCliTest, GearRatiosBeyondAnyDriveAreRefused) {
  const fs::path log = SimulatePuma("log.csv");
  std::ofstream(dir_ / "geared.urdf") << testing::GearedPaper6rUrdf({"100", "1e77", "100", "100", "100", "100"});
  const fs::path paper6r_log = dir_ / "p6.csv";
  ASSERT_EQ(Run("simulate --robot paper6r --duration 10 --rate 100 --out " + paper6r_log.string()).exit_code, 0);
  Result r = Run("identify --robot " + (dir_ / "geared.urdf").string() + " --data " + paper6r_log.string() +
                 " --friction-side actuator --out " + (dir_ / "a").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("idbench: error: " + (dir_ / "geared.urdf").string() + " (<transmission>): "
                       "transmission.actuator_from_joint[1][1]: 1e+77 rad of motor 2 per rad of joint 2, beyond any "
                       "drive (a gear ratio of magnitude at most 10000)"), std::string::npos) << r.err;
  std::ofstream(dir_ / "log.json") << R"({"files": [{"path": "log.csv"}],
    "transmission": {"reduction": [100, 100, 100000, 100, 100, 100]}})";
  r = Run("identify --robot puma560 --data " + (dir_ / "log.json").string() + " --friction-side actuator --out " +
          (dir_ / "b").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("log.json: .transmission.reduction[2]: expected a gear ratio of magnitude at most 10000 "
                       "(beyond any drive), got 100000"),
            std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "a"));
  EXPECT_FALSE(fs::exists(dir_ / "b"));
}

// A URDF link mass of 1e200 hung every identify (OLS too) on main 6ab1a0b:
// now the load refuses it at once, exit 2, naming link and field.
TEST_F(IdentifyCliTest, AbsurdMassIsRefusedAtLoad) {
  const fs::path log = SimulatePuma("log.csv");
  std::string text = WriteUrdf(MakePuma560());
  const size_t at = text.find("<mass value=\"", text.find("<mass value=\"") + 1);  // the second link's
  text.replace(at, text.find('"', at + 13) - at + 1, "<mass value=\"1e200\"");
  std::ofstream(dir_ / "heavy.urdf") << text;
  const Result r = Run("identify --robot " + (dir_ / "heavy.urdf").string() + " --data " + log.string() + " --out " +
                       (dir_ / "h").string(), "timeout 20 ");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("<inertial>/<mass> is 1e+200 kg"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "h"));
}

}  // namespace
}  // namespace idbench

namespace idbench {
namespace {

// A closed loop simulated under a PID (model feed-forward) and identified by
// the closed-loop estimators: noise-free with qd, qdd read, both recover the
// base parameters (robot file = truth) in one iteration; without the
// controller or the reference they are refused before anything runs.
TEST_F(IdentifyCliTest, ClosedLoopEstimatorsRecoverTheBaseParameters) {
  const fs::path pid = dir_ / "pid.json";
  std::ofstream(pid) << R"({"kp": [2000, 2000, 1000, 200, 200, 200], "kd": [40, 40, 20, 4, 4, 4], "ki": 50,
                           "feedforward": "model"})";
  const fs::path log = dir_ / "closed.csv";
  Result r = Run("simulate --robot puma560 --duration 4 --controller " + pid.string() + " --out " + log.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(Slurp(log).find(",qr1,"), std::string::npos);
  for (const std::string estimator : {"iv", "didim"}) {
    const fs::path out = dir_ / estimator;
    r = Run("identify --robot puma560 --data " + log.string() + " --estimator " + estimator + " --controller " +
            pid.string() + " --reference general --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = Json(out / "identified.json");
    EXPECT_EQ(j["estimator"], estimator);
    EXPECT_TRUE(j["closed_loop"]["converged"].get<bool>());
    EXPECT_LT(BaseError(j), 1e-9) << estimator;
  }
  r = Run("identify --robot puma560 --data " + log.string() + " --estimator didim --reference general --out " +
          (dir_ / "x").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--controller: the estimator didim re-simulates the closed loop"), std::string::npos) << r.err;
  r = Run("identify --robot puma560 --data " + log.string() + " --estimator iv --controller " + pid.string() +
          " --out " + (dir_ / "x").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--reference: the estimator iv"), std::string::npos) << r.err;
  std::ofstream(dir_ / "bad.json") << R"({"kp": [1, 2], "kd": 1})";
  r = Run("simulate --robot puma560 --duration 1 --controller " + (dir_ / "bad.json").string() + " --out " +
          (dir_ / "b.csv").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.json: kp: expected one value or 6 (one per joint), got 2"), std::string::npos) << r.err;
  // The PUMA's gains hold it (no warning); on paper6r over 10 s the same
  // gains lose the reference by radians: said, naming the joint, and the log
  // is still written (it is of the motion that happened).
  EXPECT_EQ(Run("simulate --robot puma560 --duration 4 --controller " + pid.string() + " --out " +
                (dir_ / "held.csv").string()).err.find("did not hold the reference"),
            std::string::npos);
  r = Run("simulate --robot paper6r --duration 10 --controller " + pid.string() + " --out " + (dir_ / "lost.csv").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("idbench: warning: the controller did not hold the reference: joint '"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "lost.csv"));
}

// A controller holds each torque to the next sample: read as t, q, τ with
// the torque paired with its own sample, a noise-free closed-loop log of the
// 3-joint table_arm (no friction: nothing but the hold in the way) leaves the
// fit half a sample off, 8e-3 of the largest base parameter; --torque-held
// reads each torque as the mean of its hold and the previous one's and the
// error falls to the filter's own floor (the same arm open loop: 1.7e-6).
TEST_F(IdentifyCliTest, HeldTorquesOfAClosedLoopIdentifyToTheFiltersFloor) {
  const std::string urdf = IDBENCH_SOURCE_DIR "/tests/data/table_arm/table_arm.urdf";
  const fs::path pid = dir_ / "pid.json";
  std::ofstream(pid) << R"({"kp": [400, 400, 200], "kd": [10, 10, 5], "feedforward": "model"})";
  const fs::path log = dir_ / "closed.csv";
  Result r = Run("simulate --robot " + urdf + " --duration 10 --controller " + pid.string() + " --no-derivatives --out " +
                 log.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run("identify --robot " + urdf + " --data " + log.string() + " --friction none --estimator ols --out " +
          (dir_ / "as_recorded").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double as_recorded = BaseError(Json(dir_ / "as_recorded" / "identified.json"));
  r = Run("identify --robot " + urdf + " --data " + log.string() + " --friction none --estimator ols --torque-held --out " +
          (dir_ / "held").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("torque held from each sample to the next (zero-order hold)"), std::string::npos) << r.out;
  const double held = BaseError(Json(dir_ / "held" / "identified.json"));
  std::printf("closed loop, t, q, tau: base parameter error %.3g as recorded, %.3g read as held\n", as_recorded, held);
  EXPECT_NEAR(as_recorded, 0.012, 0.0015);  // docs/commands/simulate.md quotes both
  EXPECT_NEAR(held, 4e-6, 1e-6);
}

// Issue 37: with noise in the loop (BIRDy's high preset: 1e-2° on q, which
// the PID feeds back, 0.1 N m on τ), read as t, q, τ with held torques,
// table_arm (no friction), 8 seeds. Measured: mean base-parameter error OLS
// 0.0256, IV 0.0243, DIDIM 0.0237 (0.0193 before DIDIM read the simulated q̈
// across the holds) — pinned here to 2 % as a regression check,
// not a ranking: over 24 seeds (BENCHMARKS.md, "σ of the closed-loop
// estimators") the three are level (OLS 0.0213, IV 0.0225, DIDIM 0.0210 over
// the converged seeds), so the independent check asserted is only that each
// closed-loop estimate stays within 25 % of least squares' mean error.
// σ against the spread over the same seeds: per base parameter the mean σ
// printed over the standard deviation of the estimates, the median over the
// parameters. Measured on these 8 seeds: OLS 1.17, IV 1.05, DIDIM 1.19 (before
// the extrapolated batch means, residual_covariance.h: IV 2.44, DIDIM 2.54).
// Eight draws estimate each spread to about ±25 % (χ² of 7 degrees of
// freedom), and OLS, right at 1.04 over 24 seeds, reads 1.17 here: the band
// asserted, 0.7 to 1.5, is that sampling error, not the issue's 25 % (checked
// over 24 seeds, BENCHMARKS.md).
TEST_F(IdentifyCliTest, ClosedLoopEstimatorsOnEightNoisyHeldTorqueSeedsAsMeasured) {
  const std::string urdf = IDBENCH_SOURCE_DIR "/tests/data/table_arm/table_arm.urdf";
  const fs::path pid = dir_ / "pid.json";
  std::ofstream(pid) << R"({"kp": [400, 400, 200], "kd": [10, 10, 5], "feedforward": "model"})";
  std::map<std::string, double> mean;
  std::map<std::string, std::vector<nlohmann::json>> fits;  // identified.json's base_parameters, per estimator
  const int n_seeds = 8;
  for (int seed = 1; seed <= n_seeds; ++seed) {
    const fs::path log = dir_ / ("noisy" + std::to_string(seed) + ".csv");
    Result r = Run("simulate --robot " + urdf + " --duration 10 --controller " + pid.string() +
                   " --no-derivatives --noise-preset high --seed " + std::to_string(seed) + " --out " + log.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const std::string estimator : {"ols", "iv", "didim"}) {
      const fs::path out = dir_ / (estimator + std::to_string(seed));
      const std::string loop = estimator == "ols" ? "" : " --controller " + pid.string() + " --reference general";
      r = Run("identify --robot " + urdf + " --data " + log.string() + " --friction none --torque-held --estimator " +
              estimator + loop + " --out " + out.string());
      ASSERT_EQ(r.exit_code, 0) << estimator << " seed " << seed << ": " << r.err;
      const nlohmann::json j = Json(out / "identified.json");
      mean[estimator] += BaseError(j) / n_seeds;
      fits[estimator].push_back(j["base_parameters"]);
    }
  }
  std::printf("mean base-parameter error over %d seeds: ols %.4g, iv %.4g, didim %.4g\n", n_seeds, mean["ols"],
              mean["iv"], mean["didim"]);
  EXPECT_LT(mean["iv"], 1.25 * mean["ols"]);
  EXPECT_LT(mean["didim"], 1.25 * mean["ols"]);
  EXPECT_NEAR(mean["ols"], 0.0256, 0.02 * 0.0256);
  EXPECT_NEAR(mean["iv"], 0.0243, 0.02 * 0.0243);
  EXPECT_NEAR(mean["didim"], 0.0237, 0.02 * 0.0237);
  // σ / spread, median over the base parameters.
  auto sigma_over_spread = [&](const std::string& estimator) {
    const std::vector<nlohmann::json>& f = fits[estimator];
    std::vector<double> ratios;
    for (size_t k = 0; k < f.front().size(); ++k) {
      double mean_value = 0.0, mean_sigma = 0.0, squares = 0.0;
      for (const nlohmann::json& b : f) mean_value += b[k]["value"].get<double>() / n_seeds;
      for (const nlohmann::json& b : f) {
        mean_sigma += b[k]["sigma"].get<double>() / n_seeds;
        squares += std::pow(b[k]["value"].get<double>() - mean_value, 2);
      }
      ratios.push_back(mean_sigma / std::sqrt(squares / (n_seeds - 1)));
    }
    std::sort(ratios.begin(), ratios.end());
    const size_t h = ratios.size() / 2;
    return ratios.size() % 2 == 1 ? ratios[h] : 0.5 * (ratios[h - 1] + ratios[h]);
  };
  const double ols = sigma_over_spread("ols"), iv = sigma_over_spread("iv"), didim = sigma_over_spread("didim");
  std::printf("sigma / spread over %d seeds, median over the base parameters: ols %.3g, iv %.3g, didim %.3g\n",
              n_seeds, ols, iv, didim);
  for (const double ratio : {ols, iv, didim}) {
    EXPECT_GT(ratio, 0.7);
    EXPECT_LT(ratio, 1.5);
  }
}

}  // namespace
}  // namespace idbench
