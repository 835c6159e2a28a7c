#pragma once
/// The storage layer of a ROS 2 bag (sqlite3 .db3 files or an MCAP file):
/// topics, and serialized messages one at a time with their log time.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace storey {

struct StorageTopic {
  std::string name;
  std::string type;        ///< as stored, e.g. "sensor_msgs/msg/Imu"
  std::string encoding;    ///< "cdr", "ros1", ...
  std::string definition;  ///< message definition when the storage has one (MCAP schema)
  std::int64_t count = 0;  ///< messages
};

struct RawMessage {
  std::size_t topic = 0;         ///< index into topics()
  std::int64_t log_time_ns = 0;  ///< record time [ns]
  std::vector<std::uint8_t> data;
};

class MessageStorage {
 public:
  virtual ~MessageStorage() = default;
  virtual const std::vector<StorageTopic>& topics() const = 0;
  /// (Re)starts reading the messages of the topics flagged in `wanted`
  /// (indexes into topics()); every topic when empty.
  virtual void select(const std::vector<bool>& wanted) = 0;
  /// The next selected message; false at the end. Throws storey::Error
  /// naming the file and place for damaged data.
  virtual bool next(RawMessage& out) = 0;
  /// Fraction read since select() in [0, 1].
  virtual double progress() const = 0;
  /// Earliest and latest log time of the storage's messages [ns] (0 when unknown).
  virtual std::int64_t beginNs() const = 0;
  virtual std::int64_t endNs() const = 0;
  /// What `storey info` shows about the storage.
  virtual std::vector<std::pair<std::string, std::string>> properties() const = 0;
  virtual std::uint64_t sizeBytes() const = 0;
};

}  // namespace storey
