// Reading a URDF: UrdfLoadOptions, AddJointLock, LoadUrdfString and
// LoadUrdfFile (urdf.h). The text is checked (urdf_document.h), parsed by
// urdfdom, and made a chain by BuildUrdfChain (urdf_chain_builder.h).
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "idbench/engine/input_file.h"
#include "idbench/engine/urdf.h"
#include "urdf_chain_builder.h"
#include "urdf_document.h"
#include "urdf_messages.h"
#include "urdf_transmissions.h"

namespace idbench {
namespace {

using internal::Format;
using internal::Quote;

}  // namespace

bool UrdfLoadOptions::IsValid(std::string* why) const {
  for (const auto& [name, value] : locked_joints) {
    if (name.empty()) {
      *why = "locked_joints: a joint name is empty";
      return false;
    }
    if (!std::isfinite(value)) {
      *why = "locked_joints " + name + ": expected a finite value, got " + Format(value);
      return false;
    }
  }
  return true;
}

bool AddJointLock(const std::string& text, UrdfLoadOptions* options, std::string* why) {
  const auto fail = [&](const std::string& what) {
    *why = "locked_joints '" + text + "': " + what;
    return false;
  };
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    return fail("expected JOINT=VALUE (VALUE in rad, or in m for a prismatic joint)");
  }
  const std::string name = text.substr(0, equals), number = text.substr(equals + 1);
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(value)) {
    return fail("expected a finite number after '=', got '" + number + "'");
  }
  if (!options->locked_joints.emplace(name, value).second) return fail("joint " + Quote(name) + " is locked twice");
  return true;
}

UrdfLoadResult LoadUrdfString(const std::string& xml, const std::string& source_name,
                               const std::string& base_directory, const UrdfLoadOptions& options) {
  // urdfdom reports why a file is invalid through console_bridge: keep the
  // first error for our one message instead of letting it print.
  struct FirstError : console_bridge::OutputHandler {
    std::string text;
    void log(const std::string& message, console_bridge::LogLevel level, const char*, int) override {
      if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && text.empty()) text = message;
    }
  } first_error;
  internal::CheckUrdfDocument(xml, source_name);
  console_bridge::useOutputHandler(&first_error);
  urdf::ModelInterfaceSharedPtr urdf;
  try {
    urdf = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    console_bridge::restorePreviousOutputHandler();
    throw std::invalid_argument(source_name + ": not a valid URDF (" + e.what() + ")");
  }
  console_bridge::restorePreviousOutputHandler();
  // urdfdom logs an element it cannot parse and loads the rest without it:
  // any error it logs refuses the file.
  if (urdf == nullptr || urdf->getRoot() == nullptr || !first_error.text.empty()) {
    throw std::invalid_argument(source_name + ": not a valid URDF" +
                                (first_error.text.empty() ? "" : " (" + first_error.text + ")"));
  }
  UrdfLoadResult result = internal::BuildUrdfChain(
      *urdf, source_name, std::filesystem::path(base_directory.empty() ? "." : base_directory), options);
  result.transmission = internal::ReadUrdfTransmissions(xml, source_name, result.model, &result.warnings);
  return result;
}

UrdfLoadResult LoadUrdfFile(const std::string& path, const UrdfLoadOptions& options) {
  return LoadUrdfString(ReadInputFile(path), path, std::filesystem::path(path).parent_path().string(), options);
}

}  // namespace idbench
