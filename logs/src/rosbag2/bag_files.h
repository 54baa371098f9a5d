// Which storage files a bag path stands for: a bag directory's metadata.yaml
// (rosbag2_bagfile_information: storage_identifier, relative_file_paths), or
// one .db3 / .mcap file.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bag_message_reader.h"

namespace idbench::internal {

struct BagFiles {
  enum class Storage { kSqlite3, kMcap };
  Storage storage = Storage::kMcap;
  std::vector<std::string> paths;  // in recording order (a split bag has several)
};

// Throws std::invalid_argument "path: what" for a metadata.yaml that cannot
// be read (a FIFO, a directory: ReadInputFile's words), a field of the wrong
// kind (storage_identifier, compression_format or a relative_file_paths entry
// that is not a string; relative_file_paths not a list, or longer than
// 10 000), an unknown storage_identifier, a compressed bag
// (compression_format), a directory without metadata.yaml (naming the .mcap
// and .db3 files it holds), or a file that is neither .db3 nor .mcap.
BagFiles FindBagFiles(const std::string& path);

// Opens one storage file. Throws std::invalid_argument "file: what", and
// OpenStreamedInputFile's message for a path that is not a regular file.
std::unique_ptr<BagMessageReader> OpenBagFile(BagFiles::Storage storage, const std::string& path);

}  // namespace idbench::internal
