// PrefetchingJointLogSource against the source it wraps, read without it (the
// independent truth): the same samples, records and layout for any request
// sizes, the same error at the same place, and a second pass after Rewind.
#include "idbench/logs/prefetching_joint_log_source.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "idbench/engine/paper6r.h"
#include "idbench/logs/open_joint_log.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

class PrefetchingJointLogSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("idbench_prefetch_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A 6-joint log of n samples at 100 Hz (t, q, tau), line `bad` (1-based,
  // header = 1) holding a field that is not a number when bad > 0.
  std::string WriteLog(int n, int bad = 0) {
    const fs::path path = dir_ / ("log" + std::to_string(n) + "_" + std::to_string(bad) + ".csv");
    std::ofstream out(path);
    out << "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n";
    for (int k = 0; k < n; ++k) {
      out << k * 0.01;
      for (int j = 0; j < 12; ++j) out << "," << (k + 2 == bad && j == 3 ? std::string("x") : std::to_string(0.001 * k + 0.1 * j));
      out << "\n";
    }
    return path.string();
  }
  // Every sample, read with requests of `request` samples.
  static JointLogChunk ReadAll(JointLogSource& source, Eigen::Index request) {
    JointLogChunk all, chunk;
    std::vector<Eigen::VectorXd> t;
    std::vector<Eigen::MatrixXd> q, tau;
    while (source.Next(request, &chunk)) {
      EXPECT_LE(chunk.samples.t.size(), request);
      EXPECT_EQ(chunk.samples.q.rows(), chunk.samples.t.size());
      t.push_back(chunk.samples.t), q.push_back(chunk.samples.q), tau.push_back(chunk.samples.tau);
      all.records.insert(all.records.end(), chunk.records.begin(), chunk.records.end());
    }
    EXPECT_EQ(chunk.samples.t.size(), 0);  // an empty chunk at the end
    Eigen::Index n = 0;
    for (const auto& v : t) n += v.size();
    all.samples.t.resize(n);
    all.samples.q.resize(n, 6);
    all.samples.tau.resize(n, 6);
    Eigen::Index at = 0;
    for (size_t b = 0; b < t.size(); ++b) {
      all.samples.t.segment(at, t[b].size()) = t[b];
      all.samples.q.middleRows(at, t[b].size()) = q[b];
      all.samples.tau.middleRows(at, t[b].size()) = tau[b];
      at += t[b].size();
    }
    return all;
  }
  fs::path dir_;
};

TEST_F(PrefetchingJointLogSourceTest, SameSamplesForAnyRequestAndBlockSize) {
  const RobotModel model = MakePaper6r();
  const std::string path = WriteLog(1000);
  const auto plain = OpenJointLog(path, model, {}, TorqueColumns::kRequired);
  const JointLogChunk truth = ReadAll(*plain, 1000000);
  ASSERT_EQ(truth.samples.t.size(), 1000);
  for (Eigen::Index block : {1, 7, 64, 1000, 5000}) {
    for (Eigen::Index request : {1, 13, 256, 4096}) {
      SCOPED_TRACE("block " + std::to_string(block) + ", request " + std::to_string(request));
      PrefetchingJointLogSource source(OpenJointLog(path, model, {}, TorqueColumns::kRequired), block);
      for (int pass = 0; pass < 2; ++pass) {  // a second pass after Rewind
        const JointLogChunk got = ReadAll(source, request);
        EXPECT_EQ(got.samples.t, truth.samples.t);
        EXPECT_EQ(got.samples.q, truth.samples.q);
        EXPECT_EQ(got.samples.tau, truth.samples.tau);
        EXPECT_EQ(got.records, truth.records);
        source.Rewind();
      }
      EXPECT_EQ(source.layout().n_dof, 6);
      EXPECT_EQ(source.layout().source, plain->layout().source);
    }
  }
}

TEST_F(PrefetchingJointLogSourceTest, AnErrorIsRaisedWhereTheSourceRaisesIt) {
  const RobotModel model = MakePaper6r();
  const std::string path = WriteLog(500, 321);  // line 321: sample 319
  std::string expected;
  try {
    const auto plain = OpenJointLog(path, model, {}, TorqueColumns::kRequired);
    ReadAll(*plain, 100);
  } catch (const std::invalid_argument& e) {
    expected = e.what();
  }
  ASSERT_NE(expected.find(":321:"), std::string::npos) << expected;
  PrefetchingJointLogSource source(OpenJointLog(path, model, {}, TorqueColumns::kRequired), 100);
  JointLogChunk chunk;
  Eigen::Index read = 0;
  try {
    while (source.Next(100, &chunk)) read += chunk.samples.t.size();
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
  EXPECT_EQ(read, 300);  // the blocks before the one holding the bad line
}

}  // namespace
}  // namespace idbench
