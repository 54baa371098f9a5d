#include "csv_fields.h"

#include <charconv>

namespace idbench::internal {

std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    std::string field = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\r' || field.back() == '\t')) field.pop_back();
    const size_t first = field.find_first_not_of(" \t");
    fields.push_back(first == std::string::npos ? "" : field.substr(first));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

void SplitFieldViews(std::string_view line, std::vector<std::string_view>* fields) {
  fields->clear();
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    std::string_view field = line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\r' || field.back() == '\t')) field.remove_suffix(1);
    while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
    fields->push_back(field);
    if (comma == std::string_view::npos) return;
    start = comma + 1;
  }
}

bool AllNumbers(const std::vector<std::string>& fields) {
  for (const std::string& f : fields) {
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || ec != std::errc() || ptr != f.data() + f.size()) return false;
  }
  return true;
}

}  // namespace idbench::internal
