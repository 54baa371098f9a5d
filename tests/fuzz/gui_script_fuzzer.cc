// Fuzzes the headless GUI's script parser (idbench gui --script): any text is
// a list of steps or one std::invalid_argument naming the line, never a
// crash, another exception or a leak.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "idbench/gui/gui_script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    idbench::gui::ParseGuiScript(text, "fuzz.txt");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
