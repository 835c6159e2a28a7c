#include "io/rosbag_structure.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include "common/error.h"
#include "io/log_format.h"

namespace storey {
namespace {

// Record opcodes of the bag format 2.0.
constexpr std::uint8_t kOpMessageData = 0x02;
constexpr std::uint8_t kOpFileHeader = 0x03;
constexpr std::uint8_t kOpIndexData = 0x04;
constexpr std::uint8_t kOpChunk = 0x05;
constexpr std::uint8_t kOpChunkInfo = 0x06;
constexpr std::uint8_t kOpConnection = 0x07;
constexpr std::uint8_t kOpMessageDefinition = 0x01;

constexpr std::uint32_t kMaxHeaderBytes = 64u << 20;  ///< far above any real record header
constexpr std::uint32_t kMinMessageRecordBytes = 8;   ///< two length fields
constexpr const char* kRepairHint = " (`rosbag reindex` may recover it)";

/// Reads byte ranges of a file through a small cache, so that walking many
/// small records costs few system calls.
class ByteSource {
 public:
  explicit ByteSource(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw Error(path + ": cannot open the file for reading");
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
  }
  std::uint64_t size() const { return size_; }

  /// Copies `n` bytes at `pos`; the caller has checked that they are in the file.
  void read(std::uint64_t pos, void* out, std::size_t n) {
    if (n == 0) return;  // (an empty cache has no data() to copy from)
    if (pos >= cache_pos_ && pos + n <= cache_pos_ + cache_.size()) {
      std::memcpy(out, cache_.data() + (pos - cache_pos_), n);
      return;
    }
    if (n > kCacheBytes) {
      readFile(pos, static_cast<char*>(out), n);
      return;
    }
    const std::uint64_t len = std::min<std::uint64_t>(kCacheBytes, size_ - pos);
    cache_.resize(len);
    cache_pos_ = pos;
    readFile(pos, cache_.data(), len);
    std::memcpy(out, cache_.data(), n);
  }

 private:
  static constexpr std::size_t kCacheBytes = 64 * 1024;
  void readFile(std::uint64_t pos, char* out, std::size_t n) {
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(pos));
    in_.read(out, static_cast<std::streamsize>(n));
    if (static_cast<std::size_t>(in_.gcount()) != n) {
      throw Error(path_ + ": read error at byte " + std::to_string(pos));
    }
  }
  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::vector<char> cache_;
  std::uint64_t cache_pos_ = 0;
};

/// One record: header fields and the place of its data.
struct Record {
  std::uint64_t pos = 0;
  std::map<std::string, std::string> fields;
  std::uint64_t data_pos = 0;
  std::uint32_t data_len = 0;
  std::uint64_t end() const { return data_pos + data_len; }
};

class BagWalker {
 public:
  explicit BagWalker(const std::string& path) : path_(path), src_(path) {}

  RosbagStructure walk();

 private:
  [[noreturn]] void fail(std::uint64_t pos, const std::string& what) const {
    throw Error(path_ + ": damaged or truncated ROS bag: " + what + " at byte " +
                std::to_string(pos));
  }
  std::uint32_t readU32(std::uint64_t pos, std::uint64_t limit, const char* what);
  /// Parses "len name=value" fields; false when malformed.
  bool parseFields(const std::vector<char>& bytes, std::map<std::string, std::string>& fields);
  Record readRecord(std::uint64_t pos, std::uint64_t limit, const char* what);
  std::uint8_t op(const Record& r, const char* what) const;
  template <typename T>
  T field(const Record& r, const std::string& name, const char* what) const;
  std::string stringField(const Record& r, const std::string& name, const char* what) const;

  void readFileHeader(RosbagStructure& out, std::uint64_t& header_end);
  void checkChunk(std::uint64_t chunk_pos, std::size_t index_records, RosbagStructure& out);
  void checkUncompressedRecords(const Record& chunk, const std::vector<std::uint32_t>& offsets);

  std::string path_;
  ByteSource src_;
  std::uint64_t index_pos_ = 0;
  std::set<std::uint32_t> connections_;
};

std::uint32_t BagWalker::readU32(std::uint64_t pos, std::uint64_t limit, const char* what) {
  if (pos + 4 > limit) fail(pos, std::string(what) + " cut short");
  std::uint32_t value;
  src_.read(pos, &value, 4);
  return value;
}

bool BagWalker::parseFields(const std::vector<char>& bytes,
                            std::map<std::string, std::string>& fields) {
  std::size_t i = 0;
  while (i < bytes.size()) {
    if (bytes.size() - i < 4) return false;
    std::uint32_t len;
    std::memcpy(&len, bytes.data() + i, 4);
    i += 4;
    if (len > bytes.size() - i) return false;
    const char* begin = bytes.data() + i;
    const char* eq = static_cast<const char*>(std::memchr(begin, '=', len));
    if (eq == nullptr) return false;
    fields[std::string(begin, eq)] = std::string(eq + 1, begin + len);
    i += len;
  }
  return true;
}

Record BagWalker::readRecord(std::uint64_t pos, std::uint64_t limit, const char* what) {
  Record r;
  r.pos = pos;
  const std::uint32_t header_len = readU32(pos, limit, what);
  if (header_len > kMaxHeaderBytes || pos + 4 + header_len + 4 > limit) {
    fail(pos, std::string(what) + " header of " + std::to_string(header_len) +
                  " bytes runs past its end");
  }
  std::vector<char> header(header_len);
  src_.read(pos + 4, header.data(), header_len);
  if (!parseFields(header, r.fields)) fail(pos, std::string(what) + " header is malformed");
  r.data_len = readU32(pos + 4 + header_len, limit, what);
  r.data_pos = pos + 8 + header_len;
  if (r.end() > limit) {
    fail(pos,
         std::string(what) + " data of " + std::to_string(r.data_len) + " bytes runs past its end");
  }
  return r;
}

std::uint8_t BagWalker::op(const Record& r, const char* what) const {
  const auto it = r.fields.find("op");
  if (it == r.fields.end() || it->second.size() != 1) fail(r.pos, std::string(what) + " has no op");
  return static_cast<std::uint8_t>(it->second[0]);
}

template <typename T>
T BagWalker::field(const Record& r, const std::string& name, const char* what) const {
  const auto it = r.fields.find(name);
  if (it == r.fields.end() || it->second.size() != sizeof(T)) {
    fail(r.pos, std::string(what) + " lacks a valid '" + name + "' field");
  }
  T value;
  std::memcpy(&value, it->second.data(), sizeof(T));
  return value;
}

std::string BagWalker::stringField(const Record& r, const std::string& name,
                                   const char* what) const {
  const auto it = r.fields.find(name);
  if (it == r.fields.end()) fail(r.pos, std::string(what) + " lacks a '" + name + "' field");
  return it->second;
}

void BagWalker::readFileHeader(RosbagStructure& out, std::uint64_t& header_end) {
  const Record header = readRecord(std::strlen(kRosbag2Magic), out.file_size, "file header");
  if (op(header, "file header") != kOpFileHeader) {
    fail(header.pos, "the first record is not a file header");
  }
  const auto encryptor = header.fields.find("encryptor");
  if (encryptor != header.fields.end() && !encryptor->second.empty() &&
      encryptor->second != "rosbag/NoEncryptor") {
    throw Error(path_ + ": encrypted ROS bag (" + encryptor->second + ") is not supported");
  }
  out.index_pos = field<std::uint64_t>(header, "index_pos", "file header");
  out.connection_count = field<std::uint32_t>(header, "conn_count", "file header");
  out.chunk_count = field<std::uint32_t>(header, "chunk_count", "file header");
  header_end = header.end();
  if (out.index_pos == 0) {
    throw Error(path_ + ": ROS bag is not indexed: its recording did not finish" + kRepairHint);
  }
  if (out.index_pos > out.file_size || out.index_pos < header_end) {
    throw Error(path_ + ": truncated or damaged ROS bag: its index should start at byte " +
                std::to_string(out.index_pos) + " but the file has " +
                std::to_string(out.file_size) + " bytes" + kRepairHint);
  }
}

RosbagStructure BagWalker::walk() {
  RosbagStructure out;
  out.file_size = src_.size();
  std::uint64_t header_end = 0;
  readFileHeader(out, header_end);
  index_pos_ = out.index_pos;

  std::uint64_t pos = out.index_pos;
  for (std::uint32_t i = 0; i < out.connection_count; ++i) {
    const Record r = readRecord(pos, out.file_size, "connection record");
    if (op(r, "connection record") != kOpConnection) fail(pos, "expected a connection record");
    connections_.insert(field<std::uint32_t>(r, "conn", "connection record"));
    stringField(r, "topic", "connection record");
    std::vector<char> data(r.data_len);
    src_.read(r.data_pos, data.data(), data.size());
    std::map<std::string, std::string> connection_header;
    if (!parseFields(data, connection_header)) fail(pos, "connection header is malformed");
    pos = r.end();
  }

  std::vector<std::pair<std::uint64_t, std::size_t>> chunks;  // position, index records after it
  for (std::uint32_t i = 0; i < out.chunk_count; ++i) {
    const Record r = readRecord(pos, out.file_size, "chunk info record");
    if (op(r, "chunk info record") != kOpChunkInfo) fail(pos, "expected a chunk info record");
    if (field<std::uint32_t>(r, "ver", "chunk info record") != 1) {
      fail(pos, "unsupported chunk info version");
    }
    const auto chunk_pos = field<std::uint64_t>(r, "chunk_pos", "chunk info record");
    // ROS time: seconds in the low 32 bits, nanoseconds in the high 32.
    auto nanoseconds = [](std::uint64_t t) {
      return static_cast<std::int64_t>(t & 0xffffffffu) * 1000000000 +
             static_cast<std::int64_t>(t >> 32);
    };
    const std::int64_t start =
        nanoseconds(field<std::uint64_t>(r, "start_time", "chunk info record"));
    const std::int64_t end = nanoseconds(field<std::uint64_t>(r, "end_time", "chunk info record"));
    if (i == 0 || start < out.start_ns) out.start_ns = start;
    if (i == 0 || end > out.end_ns) out.end_ns = end;
    const auto count = field<std::uint32_t>(r, "count", "chunk info record");
    if (static_cast<std::uint64_t>(count) * 8 != r.data_len) {
      fail(pos, "chunk info record has " + std::to_string(r.data_len) + " bytes of data for " +
                    std::to_string(count) + " connections");
    }
    if (chunk_pos < header_end || chunk_pos >= out.index_pos) {
      fail(pos, "chunk info points at byte " + std::to_string(chunk_pos) +
                    ", outside the chunk area [" + std::to_string(header_end) + ", " +
                    std::to_string(out.index_pos) + ")");
    }
    chunks.emplace_back(chunk_pos, count);
    pos = r.end();
  }

  for (const auto& [chunk_pos, index_records] : chunks) checkChunk(chunk_pos, index_records, out);
  return out;
}

void BagWalker::checkChunk(std::uint64_t chunk_pos, std::size_t index_records,
                           RosbagStructure& out) {
  const Record chunk = readRecord(chunk_pos, index_pos_, "chunk");
  if (op(chunk, "chunk") != kOpChunk) fail(chunk_pos, "expected a chunk record");
  const std::string compression = stringField(chunk, "compression", "chunk");
  const auto size = field<std::uint32_t>(chunk, "size", "chunk");
  if (compression != "none" && compression != "lz4" && compression != "bz2") {
    fail(chunk_pos, "unknown chunk compression '" + compression + "'");
  }
  if (compression == "none" && size != chunk.data_len) {
    fail(chunk_pos, "uncompressed chunk of " + std::to_string(chunk.data_len) + " bytes declares " +
                        std::to_string(size));
  }
  ++out.chunks_by_compression[compression];
  out.chunk_positions.push_back(chunk_pos);

  std::vector<std::uint32_t> offsets;
  std::uint64_t pos = chunk.end();
  for (std::size_t i = 0; i < index_records; ++i) {
    const Record r = readRecord(pos, index_pos_, "index record");
    if (op(r, "index record") != kOpIndexData) fail(pos, "expected an index record");
    if (field<std::uint32_t>(r, "ver", "index record") != 1) {
      fail(pos, "unsupported index record version");
    }
    const auto conn = field<std::uint32_t>(r, "conn", "index record");
    const auto count = field<std::uint32_t>(r, "count", "index record");
    if (connections_.count(conn) == 0)
      fail(pos, "index record of unknown connection " + std::to_string(conn));
    if (static_cast<std::uint64_t>(count) * 12 != r.data_len) {
      fail(pos, "index record has " + std::to_string(r.data_len) + " bytes of data for " +
                    std::to_string(count) + " entries");
    }
    std::vector<std::uint32_t> entries(static_cast<std::size_t>(count) * 3);
    src_.read(r.data_pos, entries.data(), r.data_len);
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t offset = entries[3 * k + 2];
      if (static_cast<std::uint64_t>(offset) + kMinMessageRecordBytes >= size) {
        fail(r.data_pos + 12 * k, "index entry points at byte " + std::to_string(offset) +
                                      " of a chunk of " + std::to_string(size) + " bytes");
      }
      offsets.push_back(offset);
    }
    out.message_count += count;
    pos = r.end();
  }
  if (compression == "none") checkUncompressedRecords(chunk, offsets);
}

void BagWalker::checkUncompressedRecords(const Record& chunk,
                                         const std::vector<std::uint32_t>& offsets) {
  std::vector<std::uint32_t> message_starts;
  std::uint64_t pos = chunk.data_pos;
  while (pos < chunk.end()) {
    const Record r = readRecord(pos, chunk.end(), "record in chunk");
    const std::uint8_t record_op = op(r, "record in chunk");
    if (record_op == kOpMessageData) {
      const auto conn = field<std::uint32_t>(r, "conn", "message record");
      if (connections_.count(conn) == 0) {
        fail(pos, "message record of unknown connection " + std::to_string(conn));
      }
      message_starts.push_back(static_cast<std::uint32_t>(pos - chunk.data_pos));
    } else if (record_op != kOpConnection && record_op != kOpMessageDefinition) {
      fail(pos, "unexpected record (op " + std::to_string(record_op) + ") in a chunk");
    }
    pos = r.end();
  }
  for (const std::uint32_t offset : offsets) {
    if (!std::binary_search(message_starts.begin(), message_starts.end(), offset)) {
      fail(chunk.data_pos + offset, "index entry does not point at a message record");
    }
  }
}

}  // namespace

RosbagStructure checkRosbagStructure(const std::string& path) {
  if (detectLogFormat(path) != LogFormat::kRosbag1) throw Error(path + ": not a ROS1 bag");
  return BagWalker(path).walk();
}

}  // namespace storey
