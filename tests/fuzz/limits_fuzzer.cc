// Fuzzes the limits JSON reader (design --limits): any text is a set of
// limits or one std::invalid_argument, never a crash, another exception or a
// leak.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/workbench/formats/limits_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const idbench::RobotModel robot = idbench::MakePuma560();
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    idbench::ParseLimitsJson(text, robot, "fuzz.json");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
