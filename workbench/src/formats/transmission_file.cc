#include "idbench/workbench/formats/transmission_file.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "idbench/engine/input_file.h"
#include "idbench/engine/json_input.h"
#include "idbench/logs/joint_log_description.h"

namespace idbench {

std::optional<Transmission> ReadTransmissionArg(const std::string& spec, const std::string& robot, int n_dof,
                                                const std::optional<Transmission>& from_urdf) {
  if (spec.empty()) return std::nullopt;
  std::optional<Transmission> out;
  if (spec == "urdf") {
    if (!from_urdf) {
      throw std::invalid_argument("transmission \"urdf\": the robot '" + robot +
                                  "' has no <transmission> elements naming its joints");
    }
    out = from_urdf;
  } else {
    // A log description with a "transmission", or the transmission alone
    // (read as one, so that one parser checks it and names its keys).
    const std::string& path = spec;
    if (!IsJointLogDescriptionPath(path)) {
      throw std::invalid_argument("transmission: expected \"urdf\" or a .json/.yaml file, got '" + path + "'");
    }
    const std::string text = ReadInputFile(path);
    const bool yaml = !path.ends_with(".json");
    bool described = false;
    if (!yaml) {
      // Checked as written first, so that a syntax error, depth or repeated
      // key is reported at its own place whichever of the two it is.
      const nlohmann::json document = ParseJsonInput(text, path);
      described = document.is_object() && document.contains("files");
    } else {
      described = text.starts_with("files:") || text.find("\nfiles:") != std::string::npos;
    }
    out = described ? ParseJointLogDescription(text, path, yaml).transmission : ParseTransmissionText(text, path, yaml);
    if (!out) throw std::invalid_argument(path + ": no \"transmission\"");
  }
  std::string why;
  if (!out->IsValid(n_dof, &why)) throw std::invalid_argument(out->source + ": " + why);
  return out;
}

}  // namespace idbench
