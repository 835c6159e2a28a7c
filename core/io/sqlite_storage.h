#pragma once
/// rosbag2's sqlite3 storage: one or more .db3 files (a split bag), each
/// with the tables rosbag2 writes (topics: id, name, type,
/// serialization_format, offered_qos_profiles; messages: id, topic_id,
/// timestamp [ns], data). Messages of all files are merged in timestamp
/// order, one row per file in memory. Files are opened read-only and
/// immutable (no lock or journal files: read-only media work).
#include <memory>
#include <string>
#include <vector>

#include "io/ros2_storage.h"

namespace storey {

/// "SQLite format 3\0", the first 16 bytes of a sqlite3 database.
bool isSqliteHeader(const std::string& head);

/// Opens the files (in the order given). Throws storey::Error naming the file
/// for a file that is not a rosbag2 sqlite3 database, or damaged.
std::unique_ptr<MessageStorage> openSqliteStorage(const std::vector<std::string>& files);

}  // namespace storey
