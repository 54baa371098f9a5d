#include "bag_files.h"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <stdexcept>

#include "db3_reader.h"
#include "idbench/engine/input_file.h"
#include "idbench/engine/printable_text.h"
#include "mcap_reader.h"
#include "yaml_input.h"

namespace idbench::internal {
namespace {

namespace fs = std::filesystem;

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A metadata.yaml field that must be a string (a YAML scalar): "" when absent.
// Throws std::invalid_argument "metadata_path: field: expected a string, got a map".
std::string StringField(const YAML::Node& node, const std::string& field, const std::string& metadata_path) {
  if (!node || node.IsNull()) return "";
  if (!node.IsScalar()) {
    throw std::invalid_argument(metadata_path + ": " + field + ": expected a string, got " +
                                (node.IsMap() ? "a map" : "a list"));
  }
  return node.Scalar();
}

// The most storage files metadata.yaml may list (a split bag has one per
// split; 10 000 is 28 hours of 10-second splits).
constexpr std::size_t kMaxBagFiles = 10'000;

BagFiles FromMetadata(const fs::path& directory, const std::string& metadata_path) {
  YAML::Node info;
  try {
    // Read as an input file (a FIFO is refused, not waited on), aliases refused before expansion.
    info = LoadYamlWithoutAliases(ReadInputFile(metadata_path), metadata_path)["rosbag2_bagfile_information"];
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(metadata_path + ": " + e.what());
  }
  if (!info || !info.IsMap()) throw std::invalid_argument(metadata_path + ": no rosbag2_bagfile_information");
  BagFiles files;
  const std::string storage = StringField(info["storage_identifier"], "storage_identifier", metadata_path);
  if (storage == "sqlite3") {
    files.storage = BagFiles::Storage::kSqlite3;
  } else if (storage == "mcap") {
    files.storage = BagFiles::Storage::kMcap;
  } else {
    throw std::invalid_argument(metadata_path + ": storage_identifier '" + storage + "', expected sqlite3 or mcap");
  }
  const std::string compression = StringField(info["compression_format"], "compression_format", metadata_path);
  if (!compression.empty()) {
    throw std::invalid_argument(metadata_path + ": compression_format '" + compression +
                                "': a compressed bag is not read (decompress it with `ros2 bag convert`)");
  }
  const YAML::Node paths = info["relative_file_paths"];
  if (paths && !paths.IsNull() && !paths.IsSequence()) {
    throw std::invalid_argument(metadata_path + ": relative_file_paths: expected a list of file names, got " +
                                (paths.IsMap() ? "a map" : "'" + PrintableText(paths.Scalar()) + "'"));
  }
  if (paths && paths.size() > kMaxBagFiles) {
    throw std::invalid_argument(metadata_path + ": relative_file_paths lists " + std::to_string(paths.size()) +
                                " files, more than the " + std::to_string(kMaxBagFiles) + " read");
  }
  for (std::size_t i = 0; paths && i < paths.size(); ++i) {
    const std::string field = "relative_file_paths[" + std::to_string(i) + "]";
    const std::string file = StringField(paths[i], field, metadata_path);
    if (file.empty()) throw std::invalid_argument(metadata_path + ": " + field + ": expected a file name, got none");
    files.paths.push_back((directory / file).string());
  }
  if (files.paths.empty()) throw std::invalid_argument(metadata_path + ": relative_file_paths lists no file");
  return files;
}

// A directory that is not a bag: says what it holds that could be read.
[[noreturn]] void FailNoMetadata(const fs::path& directory) {
  std::string storage_files;
  std::error_code error;
  int listed = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".mcap" && extension != ".db3") continue;
    if (++listed > 3) {
      storage_files += ", ...";
      break;
    }
    storage_files += (storage_files.empty() ? "" : ", ") + entry.path().filename().string();
  }
  throw std::invalid_argument(
      directory.string() + ": a directory without metadata.yaml, so not a rosbag2 bag folder" +
      (storage_files.empty() ? std::string(" (it holds no .mcap or .db3 file)")
                             : " (it holds " + storage_files + ": pass one of those files to read it alone)"));
}

}  // namespace

BagFiles FindBagFiles(const std::string& path) {
  const fs::path p(path);
  std::error_code error;
  const bool storage_name = EndsWith(path, ".db3") || EndsWith(path, ".mcap");
  if (fs::is_directory(p, error)) {
    if (fs::exists(p / "metadata.yaml", error)) return FromMetadata(p, (p / "metadata.yaml").string());
    if (!storage_name) FailNoMetadata(p);  // a directory named bag_0.mcap is refused as a directory when opened
  }
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
  // Only a regular file, refused in OpenStreamedInputFile's words before a
  // reader opens it (a FIFO would block SQLite's open and the MCAP reader's; a
  // directory named bag_0.mcap is named as one).
  ::close(OpenStreamedInputFile(path));
  try {
    if (storage == BagFiles::Storage::kSqlite3) return std::make_unique<Db3Reader>(path);
    return std::make_unique<McapReader>(path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path + ": " + e.what());
  }
}

}  // namespace idbench::internal
