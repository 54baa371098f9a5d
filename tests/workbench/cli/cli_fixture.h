// Runs the `idbench` executable as a user would (path in $IDBENCH), each test
// in its own temporary directory.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace idbench::testing {

struct Result {
  int exit_code;
  std::string out, err;
};

inline std::string Slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class CliFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* exe = std::getenv("IDBENCH");
    ASSERT_NE(exe, nullptr) << "set IDBENCH to the idbench executable";
    exe_ = exe;
    dir_ = std::filesystem::temp_directory_path() /
           ("idbench_cli_" + std::string(Info()->test_suite_name()) + "_" + Info()->name() + "_" +
            std::to_string(getpid()));  // one folder per run: checkouts may run their tests at once
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  static const ::testing::TestInfo* Info() { return ::testing::UnitTest::GetInstance()->current_test_info(); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // `prefix` runs idbench under another command (e.g. "timeout -s INT 1 ").
  Result Run(const std::string& args, const std::string& prefix = "") {
    const std::string cmd = prefix + exe_ + " " + args + " >" + (dir_ / "stdout").string() + " 2>" + (dir_ / "stderr").string();
    const int status = std::system(cmd.c_str());
    return {WEXITSTATUS(status), Slurp(dir_ / "stdout"), Slurp(dir_ / "stderr")};
  }

  // The PUMA limits of issue 3 (puma_limits.json of docs/commands/design.md):
  // qd_max 1.5 rad/s and qdd_max 4 rad/s² on joints 1-3, 3 and 8 on joints
  // 4-6, positions from the robot file. Writes them in dir_; returns the path.
  std::string PumaLimits() {
    const std::filesystem::path path = dir_ / "puma_limits.json";
    std::ofstream(path) << R"({"joints": [{"qd_max": 1.5, "qdd_max": 4}, {"qd_max": 1.5, "qdd_max": 4},
      {"qd_max": 1.5, "qdd_max": 4}, {"qd_max": 3, "qdd_max": 8}, {"qd_max": 3, "qdd_max": 8},
      {"qd_max": 3, "qdd_max": 8}]})";
    return path.string();
  }

  std::string exe_;
  std::filesystem::path dir_;
};

}  // namespace idbench::testing
