// Fuzzes the log description reader (a --data, --validate, --loaded, ...
// ending in .json, .yaml or .yml; --transmission files): any text, read as
// JSON and as YAML, is a description or one std::invalid_argument, never a
// crash, a hang, another exception, a leak, or memory beyond the corpus
// test's -rss_limit_mb (the YAML alias bomb of issue 35 item 4 expanded to
// 6 GB; 100 000 nested arrays, item 3, overflowed the stack).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "idbench/logs/joint_log_description.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A description is at most kMaxBytes (ReadJointLogDescription refuses more unread).
  if (size > static_cast<std::size_t>(idbench::JointLogDescription::kMaxBytes)) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool yaml : {false, true}) {
    try {
      idbench::ParseJointLogDescription(text, yaml ? "fuzz.yaml" : "fuzz.json", yaml);
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
