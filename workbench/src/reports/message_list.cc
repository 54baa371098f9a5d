#include "idbench/workbench/reports/message_list.h"

#include <cctype>
#include <map>

namespace idbench {

std::string MessageShape(const std::string& message) {
  std::string shape;
  int depth = 0;
  bool quoted = false;
  for (size_t i = 0; i < message.size(); ++i) {
    const char c = message[i];
    if (depth == 0 && c == '\'') {
      // A quote opens after a non-letter and closes before one (so that
      // "don't" is no quote).
      const bool after_letter = i > 0 && std::isalnum(static_cast<unsigned char>(message[i - 1]));
      if (!quoted && !after_letter) {
        quoted = true;
        shape += "'…";
        continue;
      }
      if (quoted) {
        quoted = false;
        shape += '\'';
        continue;
      }
    }
    if (quoted) continue;
    if (c == '(') {
      if (depth++ == 0) shape += "(…";
      continue;
    }
    if (c == ')' && depth > 0) {
      if (--depth == 0) shape += ')';
      continue;
    }
    if (depth == 0) shape += c;
  }
  return shape;
}

namespace {

// The first quoted part of a message ("" if none), with its quotes.
std::string FirstQuoted(const std::string& message) {
  const size_t open = message.find('\'');
  if (open == std::string::npos) return "";
  const size_t close = message.find('\'', open + 1);
  return close == std::string::npos ? "" : message.substr(open, close - open + 1);
}

}  // namespace

std::vector<std::string> CollapseRepeatedMessages(const std::vector<std::string>& messages) {
  // Groups by shape, in the order of their first message.
  std::vector<std::vector<const std::string*>> groups;
  std::map<std::string, size_t> group_of_shape;
  for (const std::string& message : messages) {
    const auto [it, added] = group_of_shape.emplace(MessageShape(message), groups.size());
    if (added) groups.emplace_back();
    groups[it->second].push_back(&message);
  }
  std::vector<std::string> out;
  for (const auto& group : groups) {
    std::string text = *group[0];
    if (group.size() > 1) {
      std::string names;
      int named = 0;
      for (size_t k = 1; k < group.size(); ++k) {
        const std::string name = FirstQuoted(*group[k]);
        if (name.empty() || names.find(name) != std::string::npos) continue;
        if (named == kMaxNamedOthers) {
          names += ", …";
          break;
        }
        names += (named++ ? ", " : "") + name;
      }
      text += " (and " + std::to_string(group.size() - 1) + " more like it" + (names.empty() ? "" : ": " + names) + ")";
    }
    out.push_back(std::move(text));
  }
  return out;
}

}  // namespace idbench
