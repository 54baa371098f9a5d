// The CSV text of a joint log, line by line: fields split on commas (no
// quoting: every field is a name or a number) and told apart as numbers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace idbench::internal {

// Splits one CSV line on commas; each field trimmed of spaces, tabs and '\r'.
std::vector<std::string> SplitFields(const std::string& line);

// The same into *fields without copying (views into `line`), for data lines.
void SplitFieldViews(std::string_view line, std::vector<std::string_view>* fields);

// Whether every field of a line is a number (a data line, not a header).
bool AllNumbers(const std::vector<std::string>& fields);

}  // namespace idbench::internal
