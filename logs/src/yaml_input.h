// Parsing a user's YAML file within bounds (log descriptions, a bag's
// metadata.yaml). yaml-cpp shares an aliased node (*name) instead of copying
// it, but anything that walks the document (converting it to JSON, dumping
// it) expands every alias: 456 bytes of nested aliases expand to 6 GB. None
// of idbench's YAML formats needs an alias, and ROS 2 writes metadata.yaml
// without them, so an alias is refused outright rather than counted.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

namespace idbench::internal {

// The first document of `text` (read from `source`, which messages name).
// Throws std::invalid_argument "source:LINE:COLUMN: an alias (*name) ..." at
// the first alias, before the document is built; YAML::Exception for a syntax
// error (yaml-cpp bounds the nesting depth itself: YAML::DeepRecursion).
YAML::Node LoadYamlWithoutAliases(const std::string& text, const std::string& source);

}  // namespace idbench::internal
