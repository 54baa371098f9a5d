// ParseJsonInput (json_input.h): the one JSON parser of user files, with the
// nesting depth bounded and repeated keys refused (issue 35, items 3 and 9).
#include "idbench/engine/json_input.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace idbench {
namespace {

// The message ParseJsonInput throws for `text`; "" when it parses.
std::string Refusal(const std::string& text) {
  try {
    ParseJsonInput(text, "f.json");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string Nested(int depth) { return std::string(static_cast<size_t>(depth), '[') + std::string(static_cast<size_t>(depth), ']'); }

// 100 000 nested arrays (200 KB, under the input size limit): refused at
// level 65 with the path there (cut), not built (on 1c4dd0f the parse succeeded and
// a message showing the value overflowed the stack). 64 levels still parse.
TEST(JsonInputTest, NestingIsBoundedAt64Levels) {
  std::string path = ".family";  // the object is level 1; the 64th array (level 65) opens in the 63rd
  for (int k = 0; k < 63; ++k) path += "[0]";
  ASSERT_EQ(path.size(), 196u);
  EXPECT_EQ(Refusal("{\"family\": " + Nested(100'000) + "}"),
            "f.json: " + path.substr(0, 120) + "… (196 bytes): more than 64 nested arrays and objects");
  // The bound exactly: 64 levels parse, 65 do not.
  const nlohmann::json deepest = ParseJsonInput(Nested(kMaxJsonDepth), "f.json");
  const nlohmann::json* inner = &deepest;
  for (int k = 1; k < kMaxJsonDepth; ++k) inner = &inner->at(0);
  EXPECT_EQ(*inner, nlohmann::json::array());
  EXPECT_NE(Refusal(Nested(kMaxJsonDepth + 1)).find(": more than 64 nested"), std::string::npos);
  EXPECT_EQ(Refusal("[[{\"a\": [{}]}]]"), "");
}

// A key given twice in one object is refused with its path (nlohmann keeps
// the last value silently: {"rate": 200, "rate": 100} read as 100 Hz);
// the same key in two objects is not a repeat.
TEST(JsonInputTest, RepeatedKeyIsRefusedWithItsPath) {
  EXPECT_EQ(Refusal(R"({"rate": 200, "rate": 100})"), "f.json: .rate: key repeated in one object (each key may be given once)");
  EXPECT_EQ(Refusal(R"({"joints": [{"qd_max": 1}, {"q_min": 0, "qd_max": 1, "qd_max": 100}]})"),
            "f.json: .joints[1].qd_max: key repeated in one object (each key may be given once)");
  const nlohmann::json ok = ParseJsonInput(R"({"a": {"x": 1}, "b": [{"x": 2}, {"x": 3}], "c": [1, [2, {"x": 4}]]})", "f.json");
  EXPECT_EQ(ok, nlohmann::json::parse(R"({"a": {"x": 1}, "b": [{"x": 2}, {"x": 3}], "c": [1, [2, {"x": 4}]]})"));
  // The path counts array elements of every kind.
  EXPECT_EQ(Refusal(R"({"c": [1, "s", null, [2], {"x": 4, "x": 5}]})"), "f.json: .c[4].x: key repeated in one object (each key may be given once)");
}

// Syntax errors and numbers out of range: one message naming the file and
// the position, without nlohmann's exception id.
TEST(JsonInputTest, SyntaxErrorsNameTheFileAndPosition) {
  EXPECT_EQ(Refusal(R"({"rate": 100, "files": [)").rfind("f.json: not valid JSON: parse error at line 1, column 25", 0), 0u);
  EXPECT_EQ(Refusal(R"({"rate": 1e999})").rfind("f.json: not valid JSON: number overflow", 0), 0u) << Refusal(R"({"rate": 1e999})");
  EXPECT_EQ(Refusal("").rfind("f.json: not valid JSON: ", 0), 0u) << Refusal("");
}

}  // namespace
}  // namespace idbench
