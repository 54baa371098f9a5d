#include "header_columns.h"

#include <map>
#include <stdexcept>

#include "column_names.h"
#include "idbench/engine/printable_text.h"

namespace idbench::internal {
namespace {

// The user's columns list as given (ranges unexpanded), for messages.
std::string JoinItems(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ",") + PrintableText(item);
  return out;
}

}  // namespace

std::vector<std::string> ReconcileColumnsWithHeader(const std::vector<std::string>& columns,
                                                    const std::vector<std::string>& items,
                                                    const std::vector<std::string>& raw_header,
                                                    const std::vector<std::string>& header, const std::string& source,
                                                    int line, std::vector<std::string>* notes) {
  const std::string where = source + ":" + std::to_string(line) + ": ";
  auto known = [&](size_t c) { return c < header.size() && !header[c].empty(); };
  if (columns.size() > raw_header.size()) {
    throw std::invalid_argument(where + "the columns list names " + std::to_string(columns.size()) +
                                " columns but the header has " + std::to_string(raw_header.size()));
  }
  // In file order: each named column agrees with an idbench header name, or renames another name.
  size_t conflict = columns.size();
  for (size_t c = 0; c < columns.size() && conflict == columns.size(); ++c) {
    if (columns[c] != "_" && known(c) && columns[c] != header[c]) conflict = c;
  }
  if (conflict == columns.size()) {
    std::string renamed;
    int n_renamed = 0;
    for (size_t c = 0; c < columns.size(); ++c) {
      if (columns[c] == "_" || known(c)) continue;
      if (n_renamed++ < 24) renamed += (renamed.empty() ? "" : ", ") + ("'" + PrintableText(raw_header[c]) + "' → " + columns[c]);
    }
    if (n_renamed > 24) renamed += ", … (" + std::to_string(n_renamed) + " in all)";
    if (n_renamed > 0) notes->push_back(source + ": columns renames the header's columns in file order: " + renamed);
    return columns;
  }
  // A subset of the header's names, taken by name.
  std::map<std::string, size_t> header_column;
  for (size_t c = 0; c < header.size(); ++c) {
    if (known(c)) header_column.emplace(header[c], c);
  }
  std::string absent;
  bool skip = false;
  for (const std::string& name : columns) {
    skip = skip || name == "_";
    if (name != "_" && !header_column.count(name) && absent.empty()) absent = name;
  }
  if (absent.empty() && !skip && columns.size() < raw_header.size()) {
    std::vector<std::string> names(raw_header.size(), "_");
    for (const std::string& name : columns) names[header_column[name]] = name;
    notes->push_back(source + ": columns " + JoinItems(items) + " taken by name from the header (" +
                     std::to_string(columns.size()) + " of its " + std::to_string(raw_header.size()) +
                     " columns; the others are not used)");
    return names;
  }
  throw std::invalid_argument(
      where + ColumnLabel(conflict, raw_header[conflict]) + ": the header names this column '" + header[conflict] +
      "' but the columns list names it '" + columns[conflict] + "'" +
      (absent.empty() ? "" : " (and the header has no column '" + absent + "')") +
      ": with a header that uses idbench's names, leave the columns list out, or give one that agrees with the "
      "header (\"_\" skips a column) or names fewer columns, all found in the header (they are then matched by name)");
}

}  // namespace idbench::internal
