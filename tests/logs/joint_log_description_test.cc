// ParseJointLogDescription (joint_log_description.h) on hostile text (issue
// 35): nesting, aliases and repeated keys bounded or refused before anything
// is built or shown, and the rate within a stated range, every message naming
// the description and the key as written in it.
#include "idbench/logs/joint_log_description.h"

#include <gtest/gtest.h>

#include <string>

#include "engine/test_util.h"

namespace idbench {
namespace {

using testing::ExpectInvalid;

std::string Refusal(const std::string& text, bool yaml = false) {
  return ExpectInvalid([&] { ParseJointLogDescription(text, yaml ? "d.yaml" : "d.json", yaml); });
}

// Issue 35 item 3: 100 000 nested arrays (200 KB, under the 1 MiB limit of a
// description). On 1c4dd0f the parse succeeded and showing the value in the
// message overflowed the stack (SIGSEGV); now refused at level 65.
TEST(JointLogDescriptionTest, DeepNestingIsRefusedBeforeItIsShown) {
  const std::string bomb = "{\"files\": " + std::string(100'000, '[') + std::string(100'000, ']') + "}";
  ASSERT_LT(bomb.size(), static_cast<size_t>(JointLogDescription::kMaxBytes));
  const std::string what = Refusal(bomb);
  EXPECT_EQ(what.rfind("d.json: .files[0][0][0]", 0), 0u) << what;
  EXPECT_NE(what.find(": more than 64 nested arrays and objects"), std::string::npos) << what;
}

// Issue 35 item 4: a YAML alias bomb, 375 bytes (9 aliases of 9 aliases, 9
// deep: 9^9 = 387 million strings once expanded; on 1c4dd0f converting it
// allocated until std::bad_alloc). Refused at the first alias, with its place.
TEST(JointLogDescriptionTest, YamlAliasesAreRefused) {
  std::string bomb = "rate: 100\nfiles: [{path: q.csv}]\nx: &a [\"lol\",\"lol\",\"lol\",\"lol\",\"lol\",\"lol\",\"lol\",\"lol\",\"lol\"]\n";
  for (char level = 'b', previous = 'a'; level <= 'i'; previous = level++) {
    std::string items;
    for (int k = 0; k < 9; ++k) items += std::string(k ? "," : "") + "*" + previous;
    bomb += std::string(1, level) + ": &" + level + " [" + items + "]\n";
  }
  ASSERT_EQ(bomb.size(), 375u);
  EXPECT_EQ(Refusal(bomb, true),
            "d.yaml:4:8: an alias (*name): aliases are not read (each would be expanded where it stands); write the "
            "value out");
  // An anchor alone is harmless and read.
  EXPECT_EQ(ParseJointLogDescription("rate: &r 100\nfiles: [{path: q.csv}]\n", "d.yaml", true).rate_hz, 100.0);
}

// Issue 35 item 9: a key given twice (on 1c4dd0f the last one won: a 200 Hz
// log read at 100 Hz), in JSON as the YAML reader already refused it.
TEST(JointLogDescriptionTest, RepeatedKeysAreRefused) {
  EXPECT_EQ(Refusal(R"({"rate": 200, "rate": 100, "files": [{"path": "q.csv"}]})"),
            "d.json: .rate: key repeated in one object (each key may be given once)");
  EXPECT_EQ(Refusal(R"({"rate": 200, "files": [{"path": "q.csv"}, {"path": "a.csv", "skip": 1, "skip": 2}]})"),
            "d.json: .files[1].skip: key repeated in one object (each key may be given once)");
  EXPECT_EQ(Refusal("rate: 200\nrate: 100\nfiles: [{path: q.csv}]\n", true), "d.yaml:2: key 'rate' repeated");
}

// Issue 35 item 18: the keys a description may have are listed as written in
// it, quoted, so that a front end's respelling of its own options
// (time_window as --time-window) leaves them alone.
TEST(JointLogDescriptionTest, UnknownKeyListsTheKeysAsWritten) {
  EXPECT_EQ(Refusal(R"({"rate": 100, "files": [{"path": "q.csv"}], "window": [0, 1]})"),
            "d.json: .window: unknown key; expected \"rate\", \"files\", \"time_window\", \"angle_unit\", "
            "\"drive_gains\", \"transmission\"");
  EXPECT_EQ(Refusal(R"({"rate": 100, "files": [{"path": "q.csv", "stide": 1}]})"),
            "d.json: .files[0].stide: unknown key; expected \"path\", \"layout\", \"stride\", \"columns\", \"skip\"");
}

// Issue 35 item 19: the rate within [1 Hz, 1 MHz], and the value shown as
// written: 1e-320 (a denormal: t = k/rate was inf on 1c4dd0f), 1e-300 (a
// message about cutoff_hz on 1c4dd0f), NaN from YAML (shown as null).
TEST(JointLogDescriptionTest, RateIsFiniteAndWithinItsRange) {
  const std::string expected = ".rate: expected a sampling rate in Hz, 1 to 1e+06, got ";
  EXPECT_EQ(Refusal(R"({"rate": 1e-320, "files": [{"path": "q.csv"}]})"), "d.json: " + expected + "1e-320");
  EXPECT_EQ(Refusal(R"({"rate": 1e-300, "files": [{"path": "q.csv"}]})"), "d.json: " + expected + "1e-300");
  EXPECT_EQ(Refusal(R"({"rate": 0.5, "files": [{"path": "q.csv"}]})"), "d.json: " + expected + "0.5");
  EXPECT_EQ(Refusal(R"({"rate": 2e6, "files": [{"path": "q.csv"}]})"), "d.json: " + expected + "2000000.0");
  EXPECT_EQ(Refusal(R"({"rate": "100", "files": [{"path": "q.csv"}]})"), "d.json: " + expected + "\"100\"");
  EXPECT_EQ(Refusal("rate: nan\nfiles: [{path: q.csv}]\n", true), "d.yaml: " + expected + "nan");
  EXPECT_EQ(Refusal("rate: -inf\nfiles: [{path: q.csv}]\n", true), "d.yaml: " + expected + "-inf");
  // Both ends of the range are allowed.
  EXPECT_EQ(ParseJointLogDescription(R"({"rate": 1, "files": [{"path": "q.csv"}]})", "d.json", false).rate_hz, 1.0);
  EXPECT_EQ(ParseJointLogDescription(R"({"rate": 1e6, "files": [{"path": "q.csv"}]})", "d.json", false).rate_hz, 1e6);
  // A value that is not UTF-8 (YAML passes any byte) is shown, not thrown as
  // nlohmann's type_error (1c4dd0f: exit 1, "[json.exception.type_error.316]").
  EXPECT_EQ(Refusal("rate: \"\xff\"\nfiles: [{path: q.csv}]\n", true), "d.yaml: " + expected + "\"\xef\xbf\xbd\"");
  // NaN elsewhere is shown as nan too.
  EXPECT_EQ(Refusal("rate: 100\nfiles: [{path: q.csv}]\ndrive_gains: [1, nan]\n", true),
            "d.yaml: .drive_gains[1]: expected a finite number, got nan");
}

}  // namespace
}  // namespace idbench
