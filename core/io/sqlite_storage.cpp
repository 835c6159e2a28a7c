// The only file of core that includes sqlite3.h.
#include "io/sqlite_storage.h"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>

#include "common/error.h"

namespace storey {
namespace {

std::string uriPath(const std::string& path) {
  std::string out = "file:";
  for (const char c : std::filesystem::absolute(path).string()) {
    if (c == '%' || c == '?' || c == '#') {
      char hex[4];
      std::snprintf(hex, sizeof(hex), "%%%02X", static_cast<unsigned char>(c));
      out += hex;
    } else {
      out += c;
    }
  }
  return out + "?immutable=1";
}

/// One .db3 file: its topics (ids local to the file) and a cursor over its messages.
class Db3File {
 public:
  explicit Db3File(std::string path) : path_(std::move(path)) {
    const int rc = sqlite3_open_v2(uriPath(path_).c_str(), &db_,
                                   SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
    if (rc != SQLITE_OK) {
      // sqlite3 allocates the handle even when opening fails, and the
      // destructor does not run for a constructor that throws.
      try {
        fail("cannot open the sqlite3 database");
      } catch (...) {
        sqlite3_close(db_);
        db_ = nullptr;
        throw;
      }
    }
  }
  ~Db3File() {
    if (stmt_ != nullptr) sqlite3_finalize(stmt_);
    if (db_ != nullptr) sqlite3_close(db_);
  }
  Db3File(const Db3File&) = delete;
  Db3File& operator=(const Db3File&) = delete;

  [[noreturn]] void fail(const std::string& what) const {
    const std::string detail = db_ != nullptr ? sqlite3_errmsg(db_) : "out of memory";
    throw Error(path_ + ": " + what + " (sqlite3: " + detail + ")" +
                (detail.find("not a database") != std::string::npos ||
                         detail.find("malformed") != std::string::npos
                     ? "; the file is damaged or truncated"
                     : ""));
  }

  sqlite3_stmt* prepare(const std::string& sql) {
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &stmt, nullptr) != SQLITE_OK) {
      const std::string detail = sqlite3_errmsg(db_);
      if (detail.find("no such table") != std::string::npos) {
        throw Error(path_ + ": not a rosbag2 database (" + detail + ")");
      }
      fail("cannot read the rosbag2 tables");
    }
    return stmt;
  }

  /// Runs `sql`, calling `row` for each result row.
  template <typename F>
  void query(const std::string& sql, F&& row) {
    // Finalized also when `row` throws (else the statement and, since
    // sqlite3_close refuses a handle with live statements, the database leak).
    const std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)> stmt(prepare(sql),
                                                                     &sqlite3_finalize);
    int rc;
    while ((rc = sqlite3_step(stmt.get())) == SQLITE_ROW) row(stmt.get());
    if (rc != SQLITE_DONE) fail("cannot read the rosbag2 tables");
  }

  static std::string text(sqlite3_stmt* stmt, int column) {
    const unsigned char* t = sqlite3_column_text(stmt, column);
    return t ? reinterpret_cast<const char*>(t) : "";
  }

  /// Starts the cursor over the messages of the topic ids (local) in `ids`.
  void start(const std::vector<std::int64_t>& ids) {
    if (stmt_ != nullptr) sqlite3_finalize(stmt_);
    stmt_ = nullptr;
    have_row_ = false;
    if (ids.empty()) return;
    std::string list;
    for (const auto id : ids) list += (list.empty() ? "" : ",") + std::to_string(id);
    stmt_ = prepare("SELECT topic_id, timestamp, data FROM messages WHERE topic_id IN (" + list +
                    ") ORDER BY timestamp, id");
    advance();
  }

  /// Steps the cursor; have_row_ tells whether a row is there.
  void advance() {
    if (stmt_ == nullptr) return;
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) {
      have_row_ = true;
      topic_id_ = sqlite3_column_int64(stmt_, 0);
      time_ns_ = sqlite3_column_int64(stmt_, 1);
      ++rows_;
      return;
    }
    have_row_ = false;
    if (rc != SQLITE_DONE) fail("cannot read message " + std::to_string(rows_ + 1));
  }

  void take(std::vector<std::uint8_t>& out) const {
    const void* blob = sqlite3_column_blob(stmt_, 2);
    const int n = sqlite3_column_bytes(stmt_, 2);
    const auto* p = static_cast<const std::uint8_t*>(blob);
    out.assign(p, p + std::max(0, n));
  }

  const std::string& path() const { return path_; }
  bool haveRow() const { return have_row_; }
  std::int64_t topicId() const { return topic_id_; }
  std::int64_t timeNs() const { return time_ns_; }
  std::int64_t rows() const { return rows_; }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* stmt_ = nullptr;
  bool have_row_ = false;
  std::int64_t topic_id_ = 0;
  std::int64_t time_ns_ = 0;
  std::int64_t rows_ = 0;
};

class SqliteStorage final : public MessageStorage {
 public:
  explicit SqliteStorage(const std::vector<std::string>& files) {
    if (files.empty()) throw Error("rosbag2: no .db3 file to read");
    std::map<std::string, std::size_t> by_name;
    bool have_time = false;
    for (const auto& path : files) {
      std::error_code ec;
      size_ += std::filesystem::file_size(path, ec);
      auto file = std::make_unique<Db3File>(path);
      std::map<std::int64_t, std::size_t> local;
      file->query("SELECT id, name, type, serialization_format FROM topics ORDER BY id",
                  [&](sqlite3_stmt* s) {
                    const std::string name = Db3File::text(s, 1);
                    auto [it, inserted] = by_name.emplace(name, topics_.size());
                    if (inserted) {
                      topics_.push_back(StorageTopic{name, Db3File::text(s, 2), Db3File::text(s, 3),
                                                     std::string(), 0});
                    }
                    local[sqlite3_column_int64(s, 0)] = it->second;
                  });
      file->query(
          "SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages GROUP BY "
          "topic_id",
          [&](sqlite3_stmt* s) {
            const auto it = local.find(sqlite3_column_int64(s, 0));
            if (it == local.end()) {
              throw Error(path + ": messages of topic id " +
                          std::to_string(sqlite3_column_int64(s, 0)) +
                          ", which the topics table does not list");
            }
            const std::int64_t count = sqlite3_column_int64(s, 1);
            topics_[it->second].count += count;
            messages_ += count;
            const std::int64_t lo = sqlite3_column_int64(s, 2), hi = sqlite3_column_int64(s, 3);
            begin_ns_ = have_time ? std::min(begin_ns_, lo) : lo;
            end_ns_ = have_time ? std::max(end_ns_, hi) : hi;
            have_time = true;
          });
      local_to_topic_.push_back(std::move(local));
      files_.push_back(std::move(file));
    }
  }

  const std::vector<StorageTopic>& topics() const override { return topics_; }

  void select(const std::vector<bool>& wanted) override {
    selected_ = 0;
    read_ = 0;
    for (std::size_t f = 0; f < files_.size(); ++f) {
      std::vector<std::int64_t> ids;
      for (const auto& [id, topic] : local_to_topic_[f]) {
        if (wanted.empty() || (topic < wanted.size() && wanted[topic])) {
          ids.push_back(id);
        }
      }
      files_[f]->start(ids);
    }
    for (std::size_t t = 0; t < topics_.size(); ++t) {
      if (wanted.empty() || (t < wanted.size() && wanted[t])) selected_ += topics_[t].count;
    }
  }

  bool next(RawMessage& out) override {
    Db3File* best = nullptr;
    std::size_t best_index = 0;
    for (std::size_t f = 0; f < files_.size(); ++f) {
      Db3File* file = files_[f].get();
      if (file->haveRow() && (best == nullptr || file->timeNs() < best->timeNs())) {
        best = file;
        best_index = f;
      }
    }
    if (best == nullptr) return false;
    const auto it = local_to_topic_[best_index].find(best->topicId());
    out.topic = it->second;
    out.log_time_ns = best->timeNs();
    best->take(out.data);
    best->advance();
    ++read_;
    return true;
  }

  double progress() const override {
    return selected_ > 0 ? std::min(1.0, static_cast<double>(read_) / selected_) : 1.0;
  }
  std::int64_t beginNs() const override { return begin_ns_; }
  std::int64_t endNs() const override { return end_ns_; }

  std::vector<std::pair<std::string, std::string>> properties() const override {
    std::string names;
    for (const auto& f : files_) {
      names += (names.empty() ? "" : ", ") + std::filesystem::path(f->path()).filename().string();
    }
    return {{"storage", "sqlite3"}, {"files", names}};
  }
  std::uint64_t sizeBytes() const override { return size_; }

 private:
  std::vector<std::unique_ptr<Db3File>> files_;
  std::vector<std::map<std::int64_t, std::size_t>> local_to_topic_;  ///< per file: id -> topic
  std::vector<StorageTopic> topics_;
  std::int64_t messages_ = 0;
  std::int64_t selected_ = 0;
  std::int64_t read_ = 0;
  std::int64_t begin_ns_ = 0;
  std::int64_t end_ns_ = 0;
  std::uint64_t size_ = 0;
};

}  // namespace

bool isSqliteHeader(const std::string& head) {
  return head.size() >= 16 && std::memcmp(head.data(), "SQLite format 3\0", 16) == 0;
}

std::unique_ptr<MessageStorage> openSqliteStorage(const std::vector<std::string>& files) {
  return std::make_unique<SqliteStorage>(files);
}

}  // namespace storey
