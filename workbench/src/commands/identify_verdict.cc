// The verdict on an identification (issue 20): whether its robot model is
// written, and the message when it is not, naming the options' fields.
#include "idbench/workbench/commands/identify_command.h"

#include <string>

namespace idbench {

bool WritesRobotModel(const IdentifyOptions& options, const IdentifyReport& report) {
  return report.identification.verdict.fit_to_load() || options.write_unverified;
}

std::string RefusedModelMessage(const IdentifyOptions& options, const IdentifyReport& report) {
  const IdentificationVerdict& verdict = report.identification.verdict;
  if (verdict.fit_to_load()) return "";
  return "the physically consistent estimate is not a robot model (" + verdict.message + "): " + verdict.cause +
         ". identified.json holds the diagnostics; identified.urdf, identified.xml and joints.yaml " +
         (options.write_unverified ? "are written anyway, as asked (write_unverified)"
                                   : "are not written (write_unverified writes them anyway)");
}

}  // namespace idbench
