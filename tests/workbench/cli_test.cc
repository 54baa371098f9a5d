// Runs the `idbench` executable as a user would (path in $IDBENCH).
#include <gtest/gtest.h>

#include "workbench/cli_fixture.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using idbench::testing::Result;
using idbench::testing::Slurp;

// Paper Table 1 (printed to 4 decimals): m, J11, J22 = J33 of B1..B6, the
// independent truth the identified values are checked against.
constexpr double kTable1[6][3] = {
    {6402.6012, 800.3251, 982.8126}, {2746.0726, 123.5733, 416.4934}, {1186.1661, 23.7233, 156.5838},
    {308.7953, 6.1759, 5.6413},      {284.2877, 5.6858, 4.8353},      {661.7042, 29.7767, 19.8511}};

double Table1(int body, const std::string& name) {
  if (name == "J11") return kTable1[body][1];
  if (name == "J22" || name == "J33") return kTable1[body][2];
  return kTable1[body][0];  // m, m_e1, m_e2, m_e3
}

class CliTest : public idbench::testing::CliFixture {
 protected:
  // Checks results.json: every identifiable parameter within tol, B1's
  // m_e1, m_e2, J22, J33 flagged with null values, all others identified.
  void ExpectPaperTables(const fs::path& results, double tol) {
    const nlohmann::json j = nlohmann::json::parse(Slurp(results));
    ASSERT_EQ(j["bodies"].size(), 6u);
    double worst = 0.0;
    int body_index = 0;
    for (const auto& body : j["bodies"]) {
      ASSERT_EQ(body["parameters"].size(), 7u);
      for (const auto& p : body["parameters"]) {
        const std::string name = p["name"];
        const bool expect_flag = body["name"] == "B1" && (name == "m_e1" || name == "m_e2" || name == "J22" || name == "J33");
        EXPECT_EQ(p["identifiable"].get<bool>(), !expect_flag) << body["name"] << "." << name;
        if (expect_flag) {
          EXPECT_TRUE(p["identified"].is_null());
          EXPECT_FALSE(p["reason"].get<std::string>().empty());
          continue;
        }
        const double truth = p["true"], identified = p["identified"];
        // Against the printed table (4 decimals), then against the exact truth.
        EXPECT_NEAR(identified, Table1(body_index, name), 5e-5) << body["name"] << "." << name;
        EXPECT_LT(std::abs(identified - truth) / truth, tol) << body["name"] << "." << name;
        worst = std::max(worst, std::abs(identified - truth) / truth);
      }
      ++body_index;
    }
    EXPECT_NEAR(j["max_rel_error"].get<double>(), worst, 1e-3 * worst + 1e-300);
    EXPECT_LT(j["max_rel_error"].get<double>(), tol);
  }

};

TEST_F(CliTest, DefaultRunReproducesThePaperFarMoreAccurately) {
  const Result r = Run("run --out " + (dir_ / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("NOT IDENTIFIABLE"), std::string::npos);
  EXPECT_NE(r.out.find("largest relative error"), std::string::npos);
  ExpectPaperTables(dir_ / "run" / "results.json", 1e-9);
  const nlohmann::json j = nlohmann::json::parse(Slurp(dir_ / "run" / "results.json"));
  EXPECT_EQ(j["sample_times"], nlohmann::json({0.3, 0.6, 0.9, 1.2, 1.5}));
  // log.csv: a header and one row per step, every row with the header's width.
  std::ifstream log(dir_ / "run" / "log.csv");
  std::string header, line;
  std::getline(log, header);
  EXPECT_EQ(header.rfind("t,q1,q2", 0), 0u);
  const auto width = std::count(header.begin(), header.end(), ',');
  int rows = 0;
  while (std::getline(log, line)) {
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), width) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, 2000);
}

TEST_F(CliTest, GeneralMotionAlsoReproducesTheTables) {
  const Result r = Run("run --motion general --out " + (dir_ / "run").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectPaperTables(dir_ / "run" / "results.json", 1e-9);
}

TEST_F(CliTest, AllSamplesAndCustomSampling) {
  Result r = Run("run --all-samples --duration 1 --dt 0.002 --out " + (dir_ / "a").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectPaperTables(dir_ / "a" / "results.json", 1e-9);
  r = Run("run --samples 0.1,0.25,0.5,0.75 --accel 45 --out " + (dir_ / "b").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectPaperTables(dir_ / "b" / "results.json", 1e-9);
}

TEST_F(CliTest, BadUsageNamesTheValueAndExitsWith2) {
  const std::pair<std::string, std::string> cases[] = {
      {"run --dt 0", "--dt"},
      {"run --dt abc", "--dt"},
      {"run --duration -1", "--duration"},
      {"run --accel 0", "--accel"},
      {"run --samples 0.3,2.5", "2.5"},
      {"run --samples 0.3,0.6", "at least 4"},
      {"run --samples 0.3,0.6,0.9,0.3", "given twice"},
      {"run --motion wobble", "wobble"},
      {"run --robot nosuch", "nosuch"},
      {"run --frobnicate", "--frobnicate"},
      {"run --dt 0.1", "stable tracking"},
      {"run --dt 1e-12 --duration 1e-11", "--dt"},
      {"run --duration 1.05 --dt 0.1", "whole number"},
      {"run --samples 0.3,0.6,0.9,0.9005", "step grid"},
      {"run --all-samples --samples 0.3,0.6,0.9,1.2", "excludes"},
      {"run --accel 1e308", "--accel"},
      {"run --samples ,", "--samples"},
      {"--frobnicate", "--frobnicate"},
      {"bogus", "bogus"},
      {"", "subcommand"},
  };
  for (const auto& [args, fragment] : cases) {
    const bool is_run = args.rfind("run", 0) == 0;
    const Result r = Run(is_run ? args + " --out " + (dir_ / "never").string() : args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << args << " -> " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << " -> " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "never")) << args;
  }
}

TEST_F(CliTest, ExistingOutputDirectoryIsNeverWiped) {
  const fs::path out = dir_ / "mine";
  fs::create_directories(out);
  std::ofstream(out / "notes.txt") << "keep me";
  const Result r = Run("run --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Slurp(out / "notes.txt"), "keep me");
  EXPECT_TRUE(fs::exists(out / "results.json"));
  // No temporary files are left behind.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(out)) ++entries;
  EXPECT_EQ(entries, 4);  // notes.txt, results.json, log.csv, figure.png
}

TEST_F(CliTest, OutputPathThatIsAFileIsRejectedWithoutTouchingIt) {
  const fs::path file = dir_ / "afile";
  std::ofstream(file) << "precious";
  const Result r = Run("run --out " + file.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << "nothing runs before the options are checked";
  EXPECT_NE(r.err.find("not a directory"), std::string::npos) << r.err;
  EXPECT_EQ(Slurp(file), "precious");
}

}  // namespace
