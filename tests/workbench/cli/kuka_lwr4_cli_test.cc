// idbench identify on logs recorded on a real KUKA LWR4+ (FloBaRoID's
// data/KUKA/HW, see ../shared/data/kuka_lwr4/README.md): 200 Hz, t, q, qd,
// qdd, τ from joint torque sensors; measurements_1 to fit, measurements_3 (a
// different trajectory) held out. Published reference (FloBaRoID's tutorial,
// the README there): its bounded physically consistent fit on measurements_1
// has a relative torque error of 2.15 %. The data are not part of the
// project: without ../shared the tests skip and say what is missing.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "workbench/cli/cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using idbench::testing::CliFixture;
using idbench::testing::Result;

const fs::path kData = fs::path(IDBENCH_SOURCE_DIR) / ".." / "shared" / "data" / "kuka_lwr4";

class KukaLwr4CliTest : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    if (!fs::exists(kData / "logs" / "measurements_1.csv"))
      GTEST_SKIP() << "real-robot data not found at " << kData.string()
                   << " (../shared/data/kuka_lwr4 beside the checkout; not part of the project)";
  }
  Result Identify(const std::string& estimator, const std::string& out) {
    return Run("identify --robot " + (kData / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string() + " --data " +
               (kData / "logs" / "measurements_1.csv").string() + " --validate " +
               (kData / "logs" / "measurements_3.csv").string() +
               " --friction viscous,coulomb,offset --estimator " + estimator + " --out " + (dir_ / out).string());
  }
  nlohmann::json Json(const std::string& out) {
    return nlohmann::json::parse(idbench::testing::Slurp(dir_ / out / "identified.json"));
  }
};

// OLS: 1.99 % on measurements_1 (FloBaRoID's bounded fit: 2.15 %; OLS is the
// unconstrained optimum, so it must be at or below any constrained fit).
TEST_F(KukaLwr4CliTest, OlsFitsAtLeastAsWellAsThePublishedBoundedFit) {
  const Result r = Identify("ols", "ols");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = Json("ols");
  EXPECT_EQ(j["n_samples"].get<int>(), 5027);
  EXPECT_LE(j["fit"]["relative_error"].get<double>(), 0.0215);
}

// Coulomb friction near zero velocity (docs/commands/identify.md): tanh(q̇/V)
// with V = 0.02 rad/s against the sign, validated on the repeated motion
// (measurements_2): fit 1.887 % against 1.990 %, validation 2.048 % against
// 2.138 %, and Fc of joints 1–5 16–27 % higher (a sign fits the steps of
// reversals with too small an Fc). TLS and IRLS on the same log predict the
// held-out one within 0.1 % of OLS (no gross outliers; IRLS converges).
TEST_F(KukaLwr4CliTest, SmoothCoulombSignFitsBetterAndRaisesFc) {
  std::map<std::string, nlohmann::json> j;
  for (const std::string& extra : {std::string("--estimator ols"), std::string("--coulomb-smoothing 0.02"),
                                   std::string("--estimator tls"), std::string("--estimator irls")}) {
    const std::string out = "cs" + std::to_string(j.size());
    const Result r = Run("identify --robot " + (kData / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string() +
                         " --data " + (kData / "logs" / "measurements_1.csv").string() + " --validate " +
                         (kData / "logs" / "measurements_2.csv").string() + " --friction viscous,coulomb,offset " +
                         extra + " --write-unverified --out " + (dir_ / out).string());
    ASSERT_EQ(r.exit_code, 0) << extra << ": " << r.err;
    j[extra] = Json(out);
  }
  const nlohmann::json& sign = j["--estimator ols"];
  const nlohmann::json& smooth = j["--coulomb-smoothing 0.02"];
  EXPECT_LT(smooth["fit"]["relative_error"].get<double>(), 0.96 * sign["fit"]["relative_error"].get<double>());
  EXPECT_LT(smooth["validation"]["relative_error"].get<double>(),
            0.97 * sign["validation"]["relative_error"].get<double>());
  auto fc = [](const nlohmann::json& result) {
    std::vector<double> out;
    for (const auto& p : result["base_parameters"]) {
      if (p["name"].get<std::string>().rfind("Fc", 0) == 0) out.push_back(p["value"]);
    }
    return out;
  };
  const std::vector<double> fc_sign = fc(sign), fc_smooth = fc(smooth);
  ASSERT_EQ(fc_sign.size(), 7u);
  for (size_t k = 0; k < 5; ++k) EXPECT_GT(fc_smooth[k], 1.1 * fc_sign[k]) << "Fc" << k + 1;
  for (const char* e : {"--estimator tls", "--estimator irls"}) {
    EXPECT_TRUE(j[e]["solve"]["converged"].get<bool>()) << e;
    EXPECT_NEAR(j[e]["validation"]["relative_error"].get<double>(), sign["validation"]["relative_error"].get<double>(),
                0.001)
        << e;
  }
}

// The plausible estimate (issue 12's targets): fit ≤ 2.5 % (measured 2.26 %),
// held-out ≤ 5.5 % (measured 5.36 %; OLS 12.7 %), every link's mass within
// 0.5–1.5 × the robot file's, every centre of mass in its link's box, and the
// optimum certified to a relative duality gap ≤ 1e-6 (measured 6.7e-10).
TEST_F(KukaLwr4CliTest, PlausibleEstimateStaysInItsBoundsAndPredictsTheHeldOutLog) {
  const Result r = Identify("pc", "pc");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = Json("pc");
  const auto& pc = j["physically_consistent"];
  EXPECT_TRUE(pc["converged"].get<bool>()) << pc["status"];
  EXPECT_LE(pc["duality_gap"].get<double>(), 1e-6);
  EXPECT_LE(j["fit"]["relative_error"].get<double>(), 0.025);
  EXPECT_LE(j["validation"]["relative_error"].get<double>(), 0.055);
  ASSERT_EQ(pc["links"].size(), 7u);
  double total = 0.0;
  for (const auto& link : pc["links"]) {
    const double m = link["mass"], m_file = link["robot_file_mass"];
    total += m;
    EXPECT_GE(m, 0.5 * m_file * (1 - 1e-9)) << link["name"];
    EXPECT_LE(m, 1.5 * m_file * (1 + 1e-9)) << link["name"];
    ASSERT_FALSE(link["com_box_B"].is_null()) << link["name"] << ": every KUKA link has geometry";
    for (int a = 0; a < 3; ++a) {
      const double c = link["com_B"][a], lo = link["com_box_B"]["min"][a], hi = link["com_box_B"]["max"][a];
      EXPECT_GE(c, lo - 1e-9) << link["name"] << " axis " << a;
      EXPECT_LE(c, hi + 1e-9) << link["name"] << " axis " << a;
      EXPECT_LT(hi - lo, 0.5) << link["name"] << ": a box around one LWR link, not the whole arm";
    }
  }
  // The robot file's moving links weigh 14.4 kg; FloBaRoID held the total
  // within 30 % of 16 kg. No link drifts to hundreds of kg (379 kg before).
  EXPECT_GT(total, 0.7 * 16.0);
  EXPECT_LT(total, 1.3 * 16.0);
}

// compare on the three recorded logs (200 Hz, 25.1 s: not a rate the
// simulation divides, which compare refused before): each log's cond from its
// recorded states, ranked, and Bullet replaying it over 25.0 s (cut to whole
// samples·dt). Measured with the identify friction terms and one torque
// noise: cond 957.42 (measurements_1), 956.63 (measurements_2), 2252.1
// (measurements_3), ranks 2, 1, 3; realised cond 950.05, 949.41, 2224.6;
// Monte-Carlo error 0.209, 0.206, 0.269. Files 1 and 2 repeat one excitation
// trajectory (README), so their cond agree within 5 %; file 3 is another one.
TEST_F(KukaLwr4CliTest, CompareRanksTheRecordedLogs) {
  std::string logs;
  for (int k = 1; k <= 3; ++k) logs += " --log " + (kData / "logs" / ("measurements_" + std::to_string(k) + ".csv")).string();
  const Result r = Run("compare --robot " + (kData / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string() + logs +
                       " --friction viscous,coulomb,offset --tau-noise 0.5 --out " + (dir_ / "c").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json c = nlohmann::json::parse(idbench::testing::Slurp(dir_ / "c" / "compare.json"));
  ASSERT_EQ(c["motions"].size(), 3u);
  std::vector<std::pair<double, int>> by_cond;
  for (const auto& m : c["motions"]) {
    EXPECT_TRUE(m["recorded"].get<bool>());
    EXPECT_EQ(m["duration"].get<double>(), 25.0);  // 25.1 s recorded
    EXPECT_TRUE(m["simulated"].get<bool>());
    EXPECT_GT(m["mean_relative_error"].get<double>(), 0.0);
    ASSERT_TRUE(m["unexcited"].empty()) << m["trajectory"];
    by_cond.emplace_back(m["designed"]["cond"].get<double>(), m["rank"].get<int>());
  }
  EXPECT_NEAR(by_cond[0].first / by_cond[1].first, 1.0, 0.05);
  std::sort(by_cond.begin(), by_cond.end());
  for (int i = 0; i < 3; ++i) EXPECT_EQ(by_cond[static_cast<size_t>(i)].second, i + 1);
}

// Issue 33: the KUKA's three logs compared with the defaults (no --tau-noise:
// the default σ is sized for its 7 joints: 0.5 N m on joints 1-3, 0.05 on 4-7),
// two of them given where motions go (recognised as recorded logs by their
// torque columns) and one with --log. The conds are those of the three logs
// all given with --log (docs/commands/compare.md's kuka example: 957.42,
// 956.63, 2252.1); the noise does not enter them.
TEST_F(KukaLwr4CliTest, CompareTakesRecordedLogsWithDefaultNoise) {
  auto log = [](int k) { return (kData / "logs" / ("measurements_" + std::to_string(k) + ".csv")).string(); };
  const Result r = Run("compare " + log(1) + " " + log(2) + " --robot " +
                       (kData / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string() + " --log " + log(3) +
                       " --friction viscous,coulomb,offset --trials 2 --out " + (dir_ / "p").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json c = nlohmann::json::parse(idbench::testing::Slurp(dir_ / "p" / "compare.json"));
  EXPECT_EQ(c["noise"]["tau"], nlohmann::json({0.5, 0.5, 0.5, 0.05, 0.05, 0.05, 0.05}));
  ASSERT_EQ(c["motions"].size(), 3u);
  const double conds[3] = {957.42, 956.63, 2252.1};
  for (size_t m = 0; m < 3; ++m) {
    EXPECT_TRUE(c["motions"][m]["recorded"].get<bool>());
    EXPECT_TRUE(c["motions"][m]["simulated"].get<bool>());
    EXPECT_NEAR(c["motions"][m]["designed"]["cond"].get<double>() / conds[m], 1.0, 1e-4);
  }
}

// Issue 34: σ is a claim to test. measurements_1 and measurements_2 record
// the same excitation twice; each identified alone (OLS), the two estimates
// of a base parameter should differ by at most 1.96 combined σ,
// √(σ₁² + σ₂²), in about 95 % of cases if σ were honest. With σ as if the
// residual were white (sigma_white): 27 % of the 64 (median difference
// 4.5 σ). With the batch-means σ from the residual as it is, at least 80 %
// (docs/commands/identify.md states the figure). --write-unverified: the
// physically consistent fit on measurements_2 costs +53 % against its OLS
// optimum (tolerance 50 %), which would exit 1; the OLS estimate is the same.
TEST_F(KukaLwr4CliTest, TwoRecordingsOfOneMotionAgreeWithinTheirSigma) {
  nlohmann::json runs[2];
  for (int k = 1; k <= 2; ++k) {
    const std::string out = "repeat" + std::to_string(k);
    const Result r = Run("identify --robot " + (kData / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string() +
                         " --data " + (kData / "logs" / ("measurements_" + std::to_string(k) + ".csv")).string() +
                         " --friction viscous,coulomb,offset --estimator ols --write-unverified --out " + (dir_ / out).string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    runs[k - 1] = Json(out);
    EXPECT_EQ(runs[k - 1]["sigma_method"]["method"], "batch_means");
  }
  const auto& a = runs[0]["base_parameters"];
  const auto& b = runs[1]["base_parameters"];
  ASSERT_EQ(a.size(), 64u);
  ASSERT_EQ(b.size(), 64u);
  int within = 0, within_white = 0;
  std::vector<double> z;
  for (size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k]["name"], b[k]["name"]);
    const double d = std::abs(a[k]["value"].get<double>() - b[k]["value"].get<double>());
    const double s = std::hypot(a[k]["sigma"].get<double>(), b[k]["sigma"].get<double>());
    const double s_white = std::hypot(a[k]["sigma_white"].get<double>(), b[k]["sigma_white"].get<double>());
    within += d <= 1.96 * s;
    within_white += d <= 1.96 * s_white;
    z.push_back(d / s);
  }
  std::sort(z.begin(), z.end());
  const double fraction = within / 64.0, fraction_white = within_white / 64.0;
  std::printf("measurements_1 vs measurements_2 (OLS): %d of 64 base parameters (%.1f %%) differ by <= 1.96 combined "
              "sigma (batch means; median difference %.2f sigma, largest %.2f); with the white-residual sigma %d "
              "(%.1f %%); n_eff %.0f and %.0f of 5027\n",
              within, 100.0 * fraction, 0.5 * (z[31] + z[32]), z.back(), within_white, 100.0 * fraction_white,
              runs[0]["sigma_method"]["n_effective"].get<double>(), runs[1]["sigma_method"]["n_effective"].get<double>());
  EXPECT_GE(fraction, 0.8);
  EXPECT_LT(fraction_white, 0.5);  // 27 %: what the white formula claimed
}

// Sequential design on the real robot's log (issue 38, done-when 1): the KUKA
// LWR4+'s measurements_1.csv (FloBaRoID's data/KUKA/HW, 200 Hz, 25.1 s; see
// ../shared/data/kuka_lwr4/README.md), friction viscous, coulomb, offset (64
// base parameters). `design --given measurements_1.csv` shapes a motion for
// the union; `simulate` records it at the log's 200 Hz; `identify --data
// measurements_1.csv --data NEW.csv` stacks both and says cond(W) of each
// log alone and of the union. Measured (2 starts × 100 evaluations, 2.1 s):
// measurements_1 alone cond(W) = 952.3, the new motion alone 135.9, the
// union 81.36 (design predicted 81.35 with its per-second weighting): the
// union at 0.086 of the log alone, where the issue asks at most half. The
// data are not part of the project: without ../shared the test skips.
TEST_F(KukaLwr4CliTest, DesignGivenTheLogHalvesTheUnionsCondition) {
  const std::string robot = "--robot " + (kData / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string() +
                            " --friction viscous,coulomb,offset";
  const std::string log = (kData / "logs" / "measurements_1.csv").string();
  // The URDF gives no acceleration limits: those of the recorded excitation's
  // range (|qd| ≤ 0.92 rad/s, |qdd| ≤ 2.8 rad/s² in measurements_1).
  std::ofstream(dir_ / "limits.json") << R"({"joints": [)" << [] {
    std::string joints;
    for (int j = 0; j < 7; ++j) joints += std::string(j ? ", " : "") + R"({"qd_max": 1.0, "qdd_max": 3.0})";
    return joints;
  }() << "]}";
  const Result design = Run("design " + robot + " --limits " + (dir_ / "limits.json").string() + " --given " + log +
                            " --starts 2 --max-evaluations 100 --quiet --out " + (dir_ / "design").string());
  ASSERT_EQ(design.exit_code, 0) << design.err;
  EXPECT_NE(design.out.find("cond(W) of the given motions alone "), std::string::npos) << design.out;
  EXPECT_NE(design.out.find("given alone  with new motion"), std::string::npos) << design.out;
  const nlohmann::json given = nlohmann::json::parse(idbench::testing::Slurp(dir_ / "design" / "design.json"))["given"];
  ASSERT_EQ(given["predicted_sigma"].size(), 64u);
  for (const auto& p : given["predicted_sigma"]) {  // information only adds: σ never grows
    EXPECT_LE(p["with_new_motion"].get<double>(), p["given_alone"].get<double>() * (1 + 1e-9)) << p["parameter"];
  }
  const double predicted_union = given["with_new_motion"]["cond"];

  const Result simulate = Run("simulate " + robot.substr(0, robot.find(" --friction")) + " --trajectory " +
                              (dir_ / "design" / "trajectory.json").string() + " --rate 200 --out " +
                              (dir_ / "new.csv").string());
  ASSERT_EQ(simulate.exit_code, 0) << simulate.err;
  const Result identify = Run("identify " + robot + " --data " + log + " --data " + (dir_ / "new.csv").string() +
                              " --estimator ols --write-unverified --out " + (dir_ / "identify").string());
  ASSERT_EQ(identify.exit_code, 0) << identify.err;
  EXPECT_NE(identify.out.find("log 1 of 2, " + log + ": 5027 samples, cond(W) = 952.3 alone"), std::string::npos)
      << identify.out;
  const nlohmann::json id = Json("identify");
  ASSERT_EQ(id["data_logs"].size(), 2u);
  const double alone = id["data_logs"][0]["cond"], both = id["cond"];
  EXPECT_NEAR(alone, 952.3, 0.1);
  EXPECT_LE(both, 0.5 * alone) << "union " << both << ", measurements_1 alone " << alone;
  // The design's prediction of the union (a second of the log weighs as a
  // second of the new motion) against the union identify stacks.
  EXPECT_NEAR(predicted_union, both, 0.1 * both);
  EXPECT_EQ(id["data_files"], nlohmann::json({log, (dir_ / "new.csv").string()}));
}

}  // namespace
