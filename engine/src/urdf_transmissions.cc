#include "urdf_transmissions.h"

#include <tinyxml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "urdf_messages.h"

namespace idbench::internal {
namespace {

std::string TextOf(const TiXmlElement* element) {
  const char* text = element ? element->GetText() : nullptr;
  std::string out = text ? text : "";
  const size_t first = out.find_first_not_of(" \t\r\n"), last = out.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? "" : out.substr(first, last - first + 1);
}

}  // namespace

std::optional<Transmission> ReadUrdfTransmissions(const std::string& xml, const std::string& source_name,
                                                  const RobotModel& model, std::vector<std::string>* warnings) {
  if (xml.find("<transmission") == std::string::npos) return std::nullopt;
  TiXmlDocument document;
  document.Parse(xml.c_str());
  const TiXmlElement* robot = document.RootElement();
  if (document.Error() || robot == nullptr) return std::nullopt;  // CheckUrdfDocument has refused it already
  const int n = model.n_dof();
  std::vector<double> reduction(static_cast<size_t>(n), 0.0);
  bool any = false;
  std::vector<std::string> file_joints;  // every joint of the file, on the chain or off it
  for (const TiXmlElement* e = robot->FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) {
    if (const char* name = e->Attribute("name")) file_joints.push_back(name);
  }
  for (const TiXmlElement* t = robot->FirstChildElement("transmission"); t; t = t->NextSiblingElement("transmission")) {
    const char* name_attribute = t->Attribute("name");
    const std::string where =
        source_name + ":" + std::to_string(t->Row()) + ": transmission " + Quote(name_attribute ? name_attribute : "");
    const TiXmlElement* joint = t->FirstChildElement("joint");
    const char* joint_name = joint ? joint->Attribute("name") : nullptr;
    int j = -1;
    for (int k = 0; k < n && joint_name; ++k) {
      if (model.link(k).joint_name == joint_name) j = k;
    }
    // A joint the file lacks (a typo) would leave its joint direct drive.
    if (joint_name == nullptr) {
      throw std::invalid_argument(where + ": no <joint name=\"...\"> in it; a transmission names the joint it drives");
    }
    if (std::find(file_joints.begin(), file_joints.end(), joint_name) == file_joints.end()) {
      throw std::invalid_argument(where + ": <joint name=\"" + PrintableText(joint_name) +
                                  "\">: the robot has no joint " + Quote(joint_name) +
                                  " (joints: " + QuotedList(file_joints) + ")");
    }
    if (j < 0) continue;  // a joint off the chain (a gripper's)
    const char* type_attribute = t->Attribute("type");
    const std::string type = t->FirstChildElement("type") ? TextOf(t->FirstChildElement("type"))
                                                          : (type_attribute ? type_attribute : "");
    if (!type.ends_with("SimpleTransmission")) {
      warnings->push_back(where + ": type '" + PrintableText(type) + "' not read (only SimpleTransmission is); joint " +
                          Quote(joint_name) + " taken as direct drive (reduction 1)");
      continue;
    }
    const TiXmlElement* actuator = t->FirstChildElement("actuator");
    const TiXmlElement* element = actuator ? actuator->FirstChildElement("mechanicalReduction") : nullptr;
    if (!element) element = t->FirstChildElement("mechanicalReduction");
    const std::string text = TextOf(element);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value) || value == 0.0) {
      throw std::invalid_argument(where + ": mechanicalReduction: expected one finite non-zero number, got '" +
                                  PrintableText(text) + "'");
    }
    if (reduction[static_cast<size_t>(j)] != 0.0) {
      throw std::invalid_argument(where + ": joint " + Quote(joint_name) + " has a transmission already");
    }
    reduction[static_cast<size_t>(j)] = value;
    any = true;
  }
  if (!any) return std::nullopt;
  std::string direct;
  for (int j = 0; j < n; ++j) {
    if (reduction[static_cast<size_t>(j)] != 0.0) continue;
    reduction[static_cast<size_t>(j)] = 1.0;
    direct += (direct.empty() ? "" : ", ") + Quote(model.link(j).joint_name);
  }
  if (!direct.empty()) {
    warnings->push_back(source_name + ": no SimpleTransmission for joint(s) " + direct +
                        ": taken as direct drive (reduction 1)");
  }
  Transmission out = Transmission::FromReduction(reduction);
  out.source = source_name + " (<transmission>)";
  return out;
}

}  // namespace idbench::internal
