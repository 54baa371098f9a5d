// A header line and a columns list together (README.md, "Joint logs").
#pragma once

#include <string>
#include <vector>

namespace idbench::internal {

// A header and a columns list together (README "Joint logs"). `header` holds
// the header's fields as idbench names ("" where the header uses other
// names). The columns list must agree with the header wherever the header
// uses idbench names (or skip the column, "_"), and may rename the others in
// order; a list of fewer columns that all appear in the header takes them by
// name. Anything else contradicts the header: throws naming both. Returns
// the name of each file column ("_": not used); notes say how it was mapped.
std::vector<std::string> ReconcileColumnsWithHeader(const std::vector<std::string>& columns,
                                                    const std::vector<std::string>& items,
                                                    const std::vector<std::string>& raw_header,
                                                    const std::vector<std::string>& header, const std::string& source,
                                                    int line, std::vector<std::string>* notes);

}  // namespace idbench::internal
