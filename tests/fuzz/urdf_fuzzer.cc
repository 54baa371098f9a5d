// Fuzzes the URDF loader: any text is either a model or one
// std::invalid_argument, never a crash, a hang, another exception or a leak.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "idbench/engine/urdf.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  try {
    // Relative mesh names resolve against a directory that does not exist.
    idbench::LoadUrdfString(xml, "fuzz.urdf", "/nonexistent-idbench-fuzz");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
