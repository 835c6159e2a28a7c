// The only file of sim that includes sqlite3.h.
#include "sim/db3_writer.h"

#include <sqlite3.h>

#include <filesystem>

#include "common/error.h"

namespace storey::sim {
namespace {

class Db3Writer final : public Ros2StorageWriter {
 public:
  explicit Db3Writer(std::string path) : path_(std::move(path)) {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    if (sqlite3_open_v2(path_.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) !=
        SQLITE_OK) {
      fail("cannot create the database");
    }
    exec("PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF;");
    exec(
        "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);"
        "INSERT INTO schema VALUES(3,'humble');"
        "CREATE TABLE metadata(id INTEGER PRIMARY KEY,metadata_version INTEGER NOT NULL,"
        "metadata TEXT NOT NULL);"
        "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,"
        "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);"
        "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,"
        "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
        "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
        "BEGIN TRANSACTION;");
    if (sqlite3_prepare_v2(db_, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?,?,?)",
                           -1, &insert_, nullptr) != SQLITE_OK) {
      fail("cannot prepare the message insert");
    }
  }
  ~Db3Writer() override {
    if (insert_ != nullptr) sqlite3_finalize(insert_);
    if (db_ != nullptr) sqlite3_close(db_);
  }

  void addTopic(int id, const std::string& name, const std::string& type,
                const std::string& /*definition*/) override {
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_prepare_v2(db_, "INSERT INTO topics VALUES (?,?,?,'cdr','')", -1, &stmt, nullptr) !=
        SQLITE_OK) {
      fail("cannot add a topic");
    }
    sqlite3_bind_int(stmt, 1, id);
    sqlite3_bind_text(stmt, 2, name.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(stmt, 3, type.c_str(), -1, SQLITE_TRANSIENT);
    const int rc = sqlite3_step(stmt);
    sqlite3_finalize(stmt);
    if (rc != SQLITE_DONE) fail("cannot add topic " + name);
  }

  void write(int id, std::int64_t log_time_ns, const std::vector<std::uint8_t>& data) override {
    sqlite3_reset(insert_);
    sqlite3_bind_int(insert_, 1, id);
    sqlite3_bind_int64(insert_, 2, log_time_ns);
    sqlite3_bind_blob(insert_, 3, data.data(), static_cast<int>(data.size()), SQLITE_STATIC);
    if (sqlite3_step(insert_) != SQLITE_DONE) fail("cannot write a message");
  }

  void close() override {
    if (db_ == nullptr) return;
    exec("COMMIT;");
    sqlite3_finalize(insert_);
    insert_ = nullptr;
    const int rc = sqlite3_close(db_);
    db_ = nullptr;
    if (rc != SQLITE_OK) throw Error(path_ + ": cannot complete the database");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ": " + what + " (sqlite3: " + (db_ ? sqlite3_errmsg(db_) : "no memory") +
                ")");
  }
  void exec(const char* sql) {
    char* message = nullptr;
    if (sqlite3_exec(db_, sql, nullptr, nullptr, &message) != SQLITE_OK) {
      const std::string text = message ? message : "?";
      sqlite3_free(message);
      throw Error(path_ + ": " + text);
    }
  }

  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_ = nullptr;
};

}  // namespace

std::unique_ptr<Ros2StorageWriter> openDb3Writer(const std::string& path) {
  return std::make_unique<Db3Writer>(path);
}

}  // namespace storey::sim
