// Parsing a user's JSON file within bounds: every JSON file idbench reads
// (log descriptions, trajectories, limits, scenes, transmissions, results and
// identified.json) goes through ParseJsonInput, so that each is refused the
// same way when it nests too deep or repeats a key.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace idbench {

// The deepest nesting of arrays and objects a JSON input may have: no
// idbench file nests more than 4 (a description's
// .transmission.actuator_from_joint[k][j]); 64 leaves room and keeps every
// recursive walk of the document (dump(), comparisons, destruction) far from
// the call stack's end.
constexpr int kMaxJsonDepth = 64;

// Parses `text` (read from `source`, which messages name) as JSON. Throws
// std::invalid_argument starting with "source: ":
//   "not valid JSON: parse error at line 1, column 5: ..." (a syntax error,
//     or a number out of a double's range such as 1e999);
//   ".a.b[2]: more than 64 nested arrays and objects" (kMaxJsonDepth);
//   ".joints[0].qd_max: key repeated in one object" (a JSON parser would
//     silently keep one of the two values).
// Paths are jq's (.key, [index]).
nlohmann::json ParseJsonInput(const std::string& text, const std::string& source);

}  // namespace idbench
