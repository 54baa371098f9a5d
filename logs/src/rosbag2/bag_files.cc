#include "bag_files.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <stdexcept>

#include "db3_reader.h"
#include "idbench/engine/input_file.h"
#include "mcap_reader.h"
#include "yaml_input.h"

namespace idbench::internal {
namespace {

namespace fs = std::filesystem;

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

BagFiles FromMetadata(const fs::path& directory, const std::string& metadata_path) {
  YAML::Node info;
  try {
    info = LoadYamlWithoutAliases(ReadInputFile(metadata_path), metadata_path)["rosbag2_bagfile_information"];
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(metadata_path + ": " + e.what());
  }
  if (!info || !info.IsMap()) throw std::invalid_argument(metadata_path + ": no rosbag2_bagfile_information");
  BagFiles files;
  const std::string storage = info["storage_identifier"] ? info["storage_identifier"].as<std::string>() : "";
  if (storage == "sqlite3") {
    files.storage = BagFiles::Storage::kSqlite3;
  } else if (storage == "mcap") {
    files.storage = BagFiles::Storage::kMcap;
  } else {
    throw std::invalid_argument(metadata_path + ": storage_identifier '" + storage + "', expected sqlite3 or mcap");
  }
  const std::string compression = info["compression_format"] ? info["compression_format"].as<std::string>() : "";
  if (!compression.empty()) {
    throw std::invalid_argument(metadata_path + ": compression_format '" + compression +
                                "': a compressed bag is not read (decompress it with `ros2 bag convert`)");
  }
  if (info["relative_file_paths"]) {
    for (const YAML::Node& file : info["relative_file_paths"]) {
      files.paths.push_back((directory / file.as<std::string>()).string());
    }
  }
  if (files.paths.empty()) throw std::invalid_argument(metadata_path + ": relative_file_paths lists no file");
  return files;
}

}  // namespace

BagFiles FindBagFiles(const std::string& path) {
  const fs::path p(path);
  if (fs::is_directory(p)) return FromMetadata(p, (p / "metadata.yaml").string());
  if (p.filename() == "metadata.yaml") return FromMetadata(p.parent_path(), path);
  BagFiles files;
  files.paths = {path};
  if (EndsWith(path, ".db3")) {
    files.storage = BagFiles::Storage::kSqlite3;
  } else if (EndsWith(path, ".mcap")) {
    files.storage = BagFiles::Storage::kMcap;
  } else {
    throw std::invalid_argument(path + ": not a rosbag2 bag (a directory with metadata.yaml, a .db3 or .mcap file)");
  }
  return files;
}

std::unique_ptr<BagMessageReader> OpenBagFile(BagFiles::Storage storage, const std::string& path) {
  try {
    if (storage == BagFiles::Storage::kSqlite3) return std::make_unique<Db3Reader>(path);
    return std::make_unique<McapReader>(path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
}

}  // namespace idbench::internal
