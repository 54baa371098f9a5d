#include "idbench/workbench/commands/field_spelling.h"

namespace idbench {

std::string SpellFields(std::string message, std::span<const FieldSpelling> table) {
  for (const auto& [field, spelling] : table) {
    const std::string f(field), to(spelling);
    const std::string quoted = "`" + f + "`";
    for (size_t at = message.find(quoted); at != std::string::npos; at = message.find(quoted, at + to.size()))
      message.replace(at, quoted.size(), to);
    const bool plain = f.find_first_of("_.") == std::string::npos;
    for (size_t at = message.find(f); at != std::string::npos; at = message.find(f, at + 1)) {
      const size_t end = at + f.size();
      bool word = (at == 0 || std::string(" (,").find(message[at - 1]) != std::string::npos) &&
                  (end == message.size() || std::string(" :,);").find(message[end]) != std::string::npos);
      if (word && plain) {
        word = end < message.size() && message[end] == ':' &&
               (at == 0 || message[at - 1] == '(' || (at >= 2 && message.compare(at - 2, 2, ": ") == 0));
      }
      if (word) {
        message.replace(at, f.size(), to);
        at += to.size() - 1;
      }
    }
  }
  return message;
}

}  // namespace idbench
