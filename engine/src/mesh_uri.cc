#include "mesh_uri.h"

#include <cstdlib>
#include <sstream>

namespace idbench::internal {

std::optional<std::filesystem::path> ResolveMeshUri(const std::string& uri, const std::filesystem::path& base_directory,
                                                    std::vector<std::string>* looked) {
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  const std::string package = "package://", file = "file://";
  if (uri.rfind(package, 0) == 0) {
    const std::string rest = uri.substr(package.size());
    const size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash), inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (const char* paths = std::getenv("ROS_PACKAGE_PATH")) {
      std::stringstream list(paths);
      for (std::string dir; std::getline(list, dir, ':');) {
        if (!dir.empty()) candidates.push_back(fs::path(dir) / name / inside);
      }
    }
    std::error_code error;
    for (fs::path a = fs::absolute(base_directory, error); !a.empty(); a = a.parent_path()) {
      if (a.filename() == name) candidates.push_back(a / inside);
      candidates.push_back(a / name / inside);
      if (a == a.parent_path()) break;
    }
  } else if (uri.rfind(file, 0) == 0) {
    candidates.push_back(fs::path(uri.substr(file.size())));
  } else if (fs::path(uri).is_absolute()) {
    candidates.push_back(fs::path(uri));
  } else {
    candidates.push_back(base_directory / uri);
  }
  for (const fs::path& c : candidates) {
    std::error_code error;
    if (fs::exists(c, error)) return fs::absolute(c, error).lexically_normal();
    looked->push_back(c.string());
  }
  return std::nullopt;
}

}  // namespace idbench::internal
