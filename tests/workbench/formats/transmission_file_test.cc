// ReadTransmissionArg (transmission_file.h) on hostile transmission files
// (issue 35 items 3 and 9): checked as written, before the wrapping into a
// log description, so that each refusal names the file's own key path.
#include "idbench/workbench/formats/transmission_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "engine/test_util.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::ExpectInvalid;

class TransmissionFileTest : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  std::string Refusal(const std::string& path) {
    return ExpectInvalid([&] { ReadTransmissionArg(path, "puma560", 6, std::nullopt); });
  }
  const fs::path dir_ = fs::path(::testing::TempDir()) / ("transmission_file_" + std::to_string(::getpid()));
};

// 100 000 nested arrays as a gear ratio: on 1c4dd0f the message showing the
// value overflowed the stack (SIGSEGV).
TEST_F(TransmissionFileTest, DeepNestingIsRefusedAtItsKey) {
  const std::string path = Write("t.json", "{\"reduction\": " + std::string(100'000, '[') + std::string(100'000, ']') + "}");
  const std::string what = Refusal(path);
  EXPECT_EQ(what.rfind(path + ": .reduction[0][0]", 0), 0u) << what;
  EXPECT_NE(what.find(": more than 64 nested arrays and objects"), std::string::npos) << what;
}

// A repeated key is refused at its own path (not the wrapper's .transmission).
TEST_F(TransmissionFileTest, RepeatedKeyIsRefused) {
  const std::string path = Write("t.json", R"({"reduction": [100, 100, 100, 100, 100, 100], "reduction": [1, 1, 1, 1, 1, 1]})");
  EXPECT_EQ(Refusal(path), path + ": .reduction: key repeated in one object (each key may be given once)");
  // A valid one still reads.
  const auto ok = ReadTransmissionArg(Write("ok.json", R"({"reduction": [1, 2, 3, 4, 5, 6]})"), "puma560", 6, std::nullopt);
  ASSERT_TRUE(ok.has_value());
  EXPECT_EQ(ok->actuator_from_joint.diagonal(), (Eigen::VectorXd(6) << 1, 2, 3, 4, 5, 6).finished());
}

}  // namespace
}  // namespace idbench
