// The verdict on an identification (issue 20): whether its robot model is
// written, and the message when it is not, in a front end's option names.
#include "idbench/workbench/commands/identify_command.h"

#include <string>

namespace idbench {

bool WritesRobotModel(const IdentifyOptions& options, const IdentifyReport& report) {
  return report.identification.verdict.fit_to_load() || options.write_unverified;
}

std::string InFrontEndTerms(std::string text, OptionNames names) {
  const bool cli = names == OptionNames::kCommandLine;
  // Longest field names first: each is a prefix of none after it.
  const std::pair<const char*, std::string> fields[] = {
      {"plausibility.com_in_geometry = false", cli ? "--com-bound none" : "com_bound='none'"},
      {"plausibility.mass_factor_min, plausibility.mass_factor_max", cli ? "--mass-range" : "mass_range"},
      {"plausibility.total_mass_tolerance", cli ? "--total-mass-tolerance" : "total_mass_tolerance"},
      {"plausibility.total_mass", cli ? "--total-mass" : "total_mass"},
      {"plausibility.prior_weight", cli ? "--prior-weight" : "prior_weight"},
      {"plausibility.cost_tolerance", cli ? "--cost-tolerance" : "cost_tolerance"},
      {"write_unverified", cli ? "--write-unverified" : "write_unverified=True"},
  };
  for (const auto& [field, name] : fields) {
    for (size_t at = text.find(field); at != std::string::npos; at = text.find(field, at + name.size()))
      text.replace(at, std::string(field).size(), name);
  }
  return text;
}

std::string RefusedModelMessage(const IdentifyOptions& options, const IdentifyReport& report, OptionNames names) {
  const IdentificationVerdict& verdict = report.identification.verdict;
  if (verdict.fit_to_load()) return "";
  return InFrontEndTerms("the physically consistent estimate is not a robot model (" + verdict.message + "): " +
                             verdict.cause + ". identified.json holds the diagnostics; identified.urdf, identified.xml and joints.yaml " +
                             (options.write_unverified ? "are written anyway, as asked (write_unverified)"
                                                       : "are not written (write_unverified writes them anyway)"),
                         names);
}

}  // namespace idbench
