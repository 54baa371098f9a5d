#include "db3_reader.h"

#include <sqlite3.h>

#include <stdexcept>

namespace idbench::internal {
namespace {

std::string Text(sqlite3_stmt* statement, int column) {
  const unsigned char* text = sqlite3_column_text(statement, column);
  return text == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(text));
}

}  // namespace

Db3Reader::Db3Reader(const std::string& path) {
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    const std::string what = Error("cannot open the SQLite3 file");
    sqlite3_close(db_);
    db_ = nullptr;
    throw std::invalid_argument(what);
  }
  // The topics table (rosbag2's sqlite3 plugin, every schema version since
  // Foxy): id, name, type, serialization_format, offered_qos_profiles, ...
  sqlite3_stmt* statement = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT id, name, type, serialization_format FROM topics ORDER BY id", -1, &statement,
                         nullptr) != SQLITE_OK) {
    const std::string what = Error("not a rosbag2 SQLite3 bag (no topics table)");
    sqlite3_close(db_);
    db_ = nullptr;
    throw std::invalid_argument(what);
  }
  while (sqlite3_step(statement) == SQLITE_ROW) {
    topic_ids_.push_back(sqlite3_column_int64(statement, 0));
    topics_.push_back({Text(statement, 1), Text(statement, 2), Text(statement, 3)});
  }
  sqlite3_finalize(statement);
}

Db3Reader::~Db3Reader() {
  sqlite3_finalize(messages_);
  sqlite3_close(db_);
}

std::string Db3Reader::Error(const std::string& what) const {
  return what + " (SQLite: " + (db_ != nullptr ? sqlite3_errmsg(db_) : "out of memory") + ")";
}

void Db3Reader::Select(const std::string& topic) {
  sqlite3_finalize(messages_);
  messages_ = nullptr;
  last_id_ = -1;
  long long topic_id = -1;
  for (size_t i = 0; i < topics_.size(); ++i) {
    if (topics_[i].name == topic) topic_id = topic_ids_[i];
  }
  // Ties in timestamp keep the order of recording (id).
  if (sqlite3_prepare_v2(db_, "SELECT timestamp, data, id FROM messages WHERE topic_id = ? ORDER BY timestamp, id",
                         -1, &messages_, nullptr) != SQLITE_OK) {
    throw std::invalid_argument(Error("not a rosbag2 SQLite3 bag (no messages table)"));
  }
  sqlite3_bind_int64(messages_, 1, topic_id);
}

bool Db3Reader::Next(BagMessage* message) {
  if (messages_ == nullptr) return false;
  const int status = sqlite3_step(messages_);
  if (status == SQLITE_DONE) return false;
  if (status != SQLITE_ROW) throw std::invalid_argument(Error("reading messages.id after " + std::to_string(last_id_)));
  message->log_time_ns = sqlite3_column_int64(messages_, 0);
  message->data = static_cast<const std::uint8_t*>(sqlite3_column_blob(messages_, 1));
  message->size = static_cast<std::size_t>(sqlite3_column_bytes(messages_, 1));
  last_id_ = sqlite3_column_int64(messages_, 2);
  return true;
}

std::string Db3Reader::LastRecord() const { return "messages.id " + std::to_string(last_id_); }

}  // namespace idbench::internal
