// A rosbag2 SQLite3 storage file (.db3) read through libsqlite3: the topics
// table, then one topic's rows of the messages table through a cursor
// ordered by (timestamp, id), one row in memory at a time.
#pragma once

#include <string>
#include <vector>

#include "bag_message_reader.h"

struct sqlite3;
struct sqlite3_stmt;

namespace idbench::internal {

class Db3Reader final : public BagMessageReader {
 public:
  // Opens the file read-only and reads its topics. Throws
  // std::invalid_argument "what" for a file that cannot be opened or is not
  // a rosbag2 database (no topics table).
  explicit Db3Reader(const std::string& path);
  ~Db3Reader() override;
  Db3Reader(const Db3Reader&) = delete;
  Db3Reader& operator=(const Db3Reader&) = delete;

  const std::vector<BagTopic>& topics() const override { return topics_; }
  void Select(const std::string& topic) override;
  bool Next(BagMessage* message) override;
  std::string LastRecord() const override;

 private:
  std::string Error(const std::string& what) const;

  sqlite3* db_ = nullptr;
  sqlite3_stmt* messages_ = nullptr;  // the cursor over the selected topic
  std::vector<BagTopic> topics_;
  std::vector<long long> topic_ids_;  // per topics_
  long long last_id_ = -1;
};

}  // namespace idbench::internal
