#include "yaml_input.h"

#include <yaml-cpp/eventhandler.h>

#include <sstream>
#include <stdexcept>

namespace idbench::internal {
namespace {

// Reads the events of a document only to find its first alias.
class AliasFinder final : public YAML::EventHandler {
 public:
  explicit AliasFinder(const std::string& source) : source_(source) {}
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override {
    throw std::invalid_argument(source_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1) +
                                ": an alias (*name): aliases are not read (each would be expanded where it stands); "
                                "write the value out");
  }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}

 private:
  const std::string& source_;
};

}  // namespace

YAML::Node LoadYamlWithoutAliases(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  AliasFinder finder(source);
  parser.HandleNextDocument(finder);
  return YAML::Load(text);
}

}  // namespace idbench::internal
