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

// A transmission file's own fields are named from its own top, and a YAML
// syntax error at its own line (before, the file was wrapped into a log
// description: ".transmission.reduction[1]" and lines shifted by 2).
TEST_F(TransmissionFileTest, FieldsAndLinesAreTheFilesOwn) {
  const std::string bad_value = Write("gear.yaml", "# gear ratios\nreduction:\n  - 100\n  - abc\n  - 100\n  - 50\n  - 50\n  - 50\n");
  EXPECT_EQ(Refusal(bad_value), bad_value + ": .reduction[1]: expected a number, got \"abc\"");
  const std::string bad_syntax = Write("syntax.yaml", "# gear ratios\nreduction: [100, 100\njoint_offset: [0]\n");
  const std::string what = Refusal(bad_syntax);
  EXPECT_EQ(what.rfind(bad_syntax + ":3:", 0), 0u) << what;  // the line yaml-cpp reports, in the file as written
  EXPECT_NE(what.find("not valid YAML"), std::string::npos) << what;
  const std::string json = Write("gear.json", R"({"reduction": [100, 100, 1e5, 50, 50, 50]})");
  EXPECT_EQ(Refusal(json), json + ": .reduction[2]: expected a gear ratio of magnitude at most 10000 (beyond any drive), "
                                  "got 100000");
  const std::string singular = Write("singular.json", R"({"actuator_from_joint": [[1, 1], [1, 1]]})");
  EXPECT_EQ(Refusal(singular).rfind(singular + ": .actuator_from_joint: not invertible", 0), 0u) << Refusal(singular);
}

}  // namespace
}  // namespace idbench
