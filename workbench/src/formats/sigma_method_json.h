// How σ was computed, as identified.json and payload.json record it
// (`sigma_method`): the method, the blocks, n_eff and the line printed.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "idbench/ident/linear_estimator.h"
#include "idbench/workbench/commands/identify_command.h"

namespace idbench {

// `output`: the file that holds sigma_white (named in the text).
inline nlohmann::json SigmaMethodJson(const CovarianceSummary& summary, const std::string& output) {
  return {{"method", ToKey(summary.method)},
          {"n_samples", summary.n_samples},
          {"block_samples", summary.block_samples},
          {"n_blocks", summary.n_blocks},
          {"n_effective", summary.n_effective},
          {"text", SigmaMethodText(summary, output)}};
}

}  // namespace idbench
