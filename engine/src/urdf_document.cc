#include "urdf_document.h"

#include <tinyxml.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <vector>

#include "idbench/engine/printable_text.h"
#include "urdf_messages.h"

namespace idbench::internal {
namespace {

enum class Sign { kAny, kNonNegative, kPositive, kNonZero };

// A numeric attribute urdfdom reads: its name, how many numbers it holds
// (3 for a vector), and the sign they need.
struct NumberRule {
  const char* attribute;
  int count;
  Sign sign;
};

const std::vector<NumberRule> kOrigin = {{"xyz", 3, Sign::kAny}, {"rpy", 3, Sign::kAny}};

// The numeric attributes of each element under <link> and <joint>.
const std::map<std::string, std::vector<NumberRule>>& Rules() {
  static const std::map<std::string, std::vector<NumberRule>> rules = {
      {"origin", kOrigin},
      {"mass", {{"value", 1, Sign::kNonNegative}}},
      {"inertia",
       {{"ixx", 1, Sign::kAny}, {"ixy", 1, Sign::kAny}, {"ixz", 1, Sign::kAny}, {"iyy", 1, Sign::kAny},
        {"iyz", 1, Sign::kAny}, {"izz", 1, Sign::kAny}}},
      {"box", {{"size", 3, Sign::kPositive}}},
      {"cylinder", {{"radius", 1, Sign::kPositive}, {"length", 1, Sign::kPositive}}},
      {"sphere", {{"radius", 1, Sign::kPositive}}},
      {"mesh", {{"scale", 3, Sign::kNonZero}}},
      {"axis", {{"xyz", 3, Sign::kAny}}},
      {"limit",
       {{"lower", 1, Sign::kAny}, {"upper", 1, Sign::kAny}, {"effort", 1, Sign::kNonNegative},
        {"velocity", 1, Sign::kNonNegative}}},
      {"dynamics", {{"damping", 1, Sign::kNonNegative}, {"friction", 1, Sign::kNonNegative}}},
      {"mimic", {{"multiplier", 1, Sign::kAny}, {"offset", 1, Sign::kAny}}},
      {"safety_controller",
       {{"soft_lower_limit", 1, Sign::kAny}, {"soft_upper_limit", 1, Sign::kAny}, {"k_position", 1, Sign::kAny},
        {"k_velocity", 1, Sign::kAny}}},
      {"calibration", {{"rising", 1, Sign::kAny}, {"falling", 1, Sign::kAny}}},
  };
  return rules;
}

// Follows the edges (a name → the next name along: a link's parent link, a
// joint's mimic leader) from every name, each name walked once. The names of
// the first loop found, from the one a walk came back to; empty when none.
template <typename Edge, typename NextOf>
std::vector<std::string> FirstLoop(const std::map<std::string, Edge>& edges, NextOf next_of) {
  enum class State { kOnWalk, kDone };
  std::map<std::string, State> state;
  for (const auto& [first, unused] : edges) {
    std::vector<std::string> walk;
    for (std::string at = first;;) {
      const auto seen = state.find(at);
      if (seen != state.end() && seen->second == State::kDone) break;
      if (seen != state.end()) return std::vector<std::string>(std::find(walk.begin(), walk.end(), at), walk.end());
      const auto edge = edges.find(at);
      if (edge == edges.end()) break;
      state[at] = State::kOnWalk;
      walk.push_back(at);
      at = next_of(edge->second);
    }
    for (const std::string& name : walk) state[name] = State::kDone;
  }
  return {};
}

const char* SignText(Sign sign) {
  switch (sign) {
    case Sign::kNonNegative: return " >= 0";
    case Sign::kPositive: return " > 0";
    case Sign::kNonZero: return ", not 0";
    case Sign::kAny: break;
  }
  return "";
}

class DocumentCheck {
 public:
  explicit DocumentCheck(const std::string& source) : source_(source) {}

  void Run(const std::string& xml) {
    if (const size_t nul = xml.find('\0'); nul != std::string::npos) {
      throw std::invalid_argument(source_ + ": not a valid URDF: not XML: a NUL byte at offset " + std::to_string(nul) +
                                  " (a binary file?); a URDF is an XML file with a <robot> element");
    }
    // TinyXML steps over a UTF-8 sequence by its first byte's length, also
    // past the end of the text when the sequence is cut (a heap over-read
    // libFuzzer found): only UTF-8 reaches it.
    if (const size_t bad = FindInvalidUtf8(xml); bad != std::string::npos) {
      const int line = 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + static_cast<long>(bad), '\n'));
      char byte[8];
      std::snprintf(byte, sizeof(byte), "0x%02x", static_cast<unsigned char>(xml[bad]));
      Fail(line, std::string("not a valid URDF: byte ") + byte + " at offset " + std::to_string(bad) +
                     " is not UTF-8; a URDF is UTF-8 text");
    }
    TiXmlDocument document;
    document.Parse(xml.c_str());
    if (document.Error() && document.ErrorId() == TiXmlBase::TIXML_ERROR_DOCUMENT_EMPTY) {
      throw std::invalid_argument(source_ + ": not a valid URDF: not XML: no element in it; it starts with '" + PrintableText(xml, 40) +
                                  "'; a URDF is an XML file with a <robot> element");
    }
    if (document.Error()) {
      throw std::invalid_argument(source_ + ": not a valid URDF: not XML (line " + std::to_string(document.ErrorRow()) + ", column " +
                                  std::to_string(document.ErrorCol()) + ": " + document.ErrorDesc() +
                                  "); a URDF is an XML file with a <robot> element");
    }
    const TiXmlElement* robot = document.RootElement();
    if (robot == nullptr || robot->ValueStr() != "robot") {
      throw std::invalid_argument(source_ + ": not a valid URDF: the XML's root element is not <robot>" +
                                  (robot == nullptr ? std::string() : ", got <" + PrintableText(robot->ValueStr()) + ">") +
                                  "; a URDF describes one <robot>");
    }
    for (const TiXmlElement* e = robot->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
      if (e->ValueStr() != "link" && e->ValueStr() != "joint") continue;
      const char* name = e->Attribute("name");
      const std::string where = e->ValueStr() + " '" + PrintableText(name == nullptr ? "" : name) + "': ";
      CheckNumbersBelow(*e, where);
      if (e->ValueStr() == "joint") AddJoint(*e, where);
    }
    CheckNoLoop();
    CheckMimics(*robot);
  }

 private:
  // A joint's edge from its parent link to its child link.
  struct Edge {
    std::string joint, parent;
    int line;
  };

  [[noreturn]] void Fail(int line, const std::string& what) const {
    throw std::invalid_argument(source_ + ":" + std::to_string(line) + ": " + what);
  }

  // Every element below `element` (any depth) with rules.
  void CheckNumbersBelow(const TiXmlElement& element, const std::string& where) const {
    std::vector<const TiXmlElement*> stack{&element};
    while (!stack.empty()) {
      const TiXmlElement* e = stack.back();
      stack.pop_back();
      if (const auto it = Rules().find(e->ValueStr()); it != Rules().end() && e != &element) {
        for (const NumberRule& rule : it->second) CheckNumbers(*e, rule, where);
      }
      for (const TiXmlElement* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement()) {
        stack.push_back(c);
      }
    }
  }

  void CheckNumbers(const TiXmlElement& e, const NumberRule& rule, const std::string& where) const {
    const char* text = e.Attribute(rule.attribute);
    if (text == nullptr) return;
    const std::string expected = rule.count == 1 ? "one finite number" : std::to_string(rule.count) + " finite numbers";
    const auto fail = [&] {
      Fail(e.Row(), where + "<" + e.ValueStr() + " " + rule.attribute + ">: expected " + expected + SignText(rule.sign) +
                        ", got '" + PrintableText(text) + "'");
    };
    const char* p = text;
    for (int k = 0; k < rule.count; ++k) {
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(p, &end);
      if (end == p || errno == ERANGE || !std::isfinite(value)) fail();
      if ((rule.sign == Sign::kNonNegative && !(value >= 0.0)) || (rule.sign == Sign::kPositive && !(value > 0.0)) ||
          (rule.sign == Sign::kNonZero && value == 0.0)) {
        fail();
      }
      p = end;
    }
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
    if (*p != '\0') fail();
  }

  void AddJoint(const TiXmlElement& joint, const std::string& where) {
    const TiXmlElement* parent = joint.FirstChildElement("parent");
    const TiXmlElement* child = joint.FirstChildElement("child");
    const char* parent_link = parent == nullptr ? nullptr : parent->Attribute("link");
    const char* child_link = child == nullptr ? nullptr : child->Attribute("link");
    if (parent_link == nullptr || child_link == nullptr) return;  // urdfdom names what is missing
    const char* name = joint.Attribute("name");
    const std::string joint_name = name == nullptr ? "" : name;
    const auto [it, added] = parent_of_.emplace(child_link, Edge{joint_name, parent_link, joint.Row()});
    if (!added) {
      Fail(joint.Row(), where + "its child link '" + PrintableText(child_link) + "' already hangs from joint '" +
                            PrintableText(it->second.joint) + "' (line " + std::to_string(it->second.line) +
                            "); each link hangs from one joint (a URDF is a tree)");
    }
  }

  // Every <mimic joint="..."> names another joint of the file (a typo would
  // leave the joint free, or follow nothing), and following the leaders ends
  // at a joint that mimics none.
  void CheckMimics(const TiXmlElement& robot) const {
    std::vector<std::string> joints;
    for (const TiXmlElement* e = robot.FirstChildElement("joint"); e != nullptr; e = e->NextSiblingElement("joint")) {
      if (const char* name = e->Attribute("name")) joints.push_back(name);
    }
    std::vector<std::string> sorted = joints;
    std::sort(sorted.begin(), sorted.end());
    struct Mimic {
      std::string leader;
      int line;
    };
    std::map<std::string, Mimic> mimic_of;  // by joint
    for (const TiXmlElement* e = robot.FirstChildElement("joint"); e != nullptr; e = e->NextSiblingElement("joint")) {
      const TiXmlElement* mimic = e->FirstChildElement("mimic");
      const char* leader = mimic == nullptr ? nullptr : mimic->Attribute("joint");
      if (leader == nullptr) continue;  // urdfdom names what is missing
      const char* name = e->Attribute("name");
      const std::string joint = name == nullptr ? "" : name;
      const std::string where = "joint " + Quote(joint) + ": <mimic joint=\"" + PrintableText(leader) + "\">: ";
      if (leader == joint) Fail(mimic->Row(), where + "a joint cannot mimic itself; name the joint it follows");
      if (!std::binary_search(sorted.begin(), sorted.end(), std::string(leader))) {
        Fail(mimic->Row(), where + "the file has no joint " + Quote(leader) + " (joints: " + QuotedList(joints) +
                               "); name the joint it follows");
      }
      mimic_of.emplace(joint, Mimic{leader, mimic->Row()});
    }
    // Leaders followed from every mimic joint.
    const std::vector<std::string> loop = FirstLoop(mimic_of, [](const Mimic& mimic) { return mimic.leader; });
    if (!loop.empty()) {
      const Mimic& mimic = mimic_of.at(loop.front());
      Fail(mimic.line, "joint " + Quote(loop.front()) + ": <mimic joint=\"" + PrintableText(mimic.leader) +
                           "\">: joints " + QuotedList(loop) +
                           " mimic each other in a loop; one of them must follow a joint that mimics none");
    }
  }

  // Walks up from every link through the joints it hangs from; coming back
  // to a link of the same walk is a loop.
  void CheckNoLoop() const {
    const std::vector<std::string> loop = FirstLoop(parent_of_, [](const Edge& edge) { return edge.parent; });
    if (!loop.empty()) FailLoop(loop, loop.front());
  }

  [[noreturn]] void FailLoop(const std::vector<std::string>& walk, const std::string& again) const {
    std::string links = "'" + PrintableText(again) + "'", joints;
    bool in_loop = false;
    for (const std::string& link : walk) {
      in_loop = in_loop || link == again;
      if (!in_loop) continue;
      const Edge& edge = parent_of_.at(link);
      links += " ← '" + PrintableText(edge.parent) + "'";
      joints += (joints.empty() ? "'" : ", '") + PrintableText(edge.joint) + "'";
    }
    Fail(parent_of_.at(again).line, "joints " + joints + " form a loop: link " + links +
                                        "; a URDF is a tree, remove one of these joints");
  }

  const std::string& source_;
  std::map<std::string, Edge> parent_of_;  // by child link
};

}  // namespace

void CheckUrdfDocument(const std::string& xml, const std::string& source_name) {
  DocumentCheck(source_name).Run(xml);
}

}  // namespace idbench::internal
