// paper6r's URDF (engine/robots/paper6r.urdf) with a ros_control
// SimpleTransmission on each joint O1..O6, its <mechanicalReduction> as
// given (text, so that a test may write "1e77"). Shared by the tests of the
// commands and the GUI that read a URDF's transmission.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace idbench::testing {

inline std::string GearedPaper6rUrdf(const std::vector<std::string>& reductions) {
  std::ifstream in(std::filesystem::path(IDBENCH_SOURCE_DIR) / "engine" / "robots" / "paper6r.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  std::string transmissions;
  for (size_t j = 0; j < reductions.size(); ++j) {
    const std::string n = std::to_string(j + 1);
    transmissions += "<transmission name=\"t" + n + "\"><type>transmission_interface/SimpleTransmission</type>"
                     "<joint name=\"O" + n + "\"/><actuator name=\"m" + n + "\"><mechanicalReduction>" +
                     reductions[j] + "</mechanicalReduction></actuator></transmission>\n";
  }
  urdf.insert(urdf.rfind("</robot>"), transmissions);
  return urdf;
}

}  // namespace idbench::testing
