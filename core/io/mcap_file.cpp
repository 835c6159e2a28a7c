// The only file of core that includes zstd, lz4 and zlib (CRC-32).
#include "io/mcap_file.h"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "common/error.h"
#include "common/log.h"

namespace storey {
namespace {

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kStatistics = 0x0B,
  kDataEnd = 0x0F,
};

/// Record header: opcode (1) + content length (8).
constexpr std::size_t kRecordHeader = 9;
/// Footer content: summary_start, summary_offset_start, summary_crc.
constexpr std::size_t kFooterContent = 20;
/// Largest decompressed chunk accepted [bytes].
constexpr std::uint64_t kMaxChunkBytes = 1ULL << 32;

const char* opcodeName(std::uint8_t op) {
  switch (op) {
    case kHeader:
      return "Header";
    case kFooter:
      return "Footer";
    case kSchema:
      return "Schema";
    case kChannel:
      return "Channel";
    case kMessage:
      return "Message";
    case kChunk:
      return "Chunk";
    case 0x07:
      return "Message Index";
    case 0x08:
      return "Chunk Index";
    case 0x09:
      return "Attachment";
    case 0x0A:
      return "Attachment Index";
    case kStatistics:
      return "Statistics";
    case 0x0C:
      return "Metadata";
    case 0x0D:
      return "Metadata Index";
    case 0x0E:
      return "Summary Offset";
    case kDataEnd:
      return "Data End";
  }
  return "unknown";
}

std::uint32_t crc32Of(std::uint32_t crc, const std::uint8_t* data, std::size_t n) {
  while (n > 0) {
    const auto step = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    crc = static_cast<std::uint32_t>(::crc32(crc, data, step));
    data += step;
    n -= step;
  }
  return crc;
}

/// Bounds-checked little-endian reads of one record's content.
class Fields {
 public:
  Fields(const std::uint8_t* data, std::size_t size, std::string where)
      : data_(data), size_(size), where_(std::move(where)) {}

  void need(std::size_t n, const char* field) const {
    if (n > size_ - pos_) {
      throw Error(where_ + ": field '" + field + "' runs past the end of the record (needs " +
                  std::to_string(n) + " bytes, " + std::to_string(size_ - pos_) + " left)");
    }
  }
  std::uint64_t uint(std::size_t bytes, const char* field) {
    need(bytes, field);
    std::uint64_t v = 0;
    for (std::size_t k = 0; k < bytes; ++k) v |= std::uint64_t{data_[pos_ + k]} << (8 * k);
    pos_ += bytes;
    return v;
  }
  std::uint16_t u16(const char* f) { return static_cast<std::uint16_t>(uint(2, f)); }
  std::uint32_t u32(const char* f) { return static_cast<std::uint32_t>(uint(4, f)); }
  std::uint64_t u64(const char* f) { return uint(8, f); }
  std::string string(const char* field) {
    const std::uint32_t n = u32(field);
    need(n, field);
    std::string s(reinterpret_cast<const char*>(data_ + pos_), n);
    pos_ += n;
    return s;
  }
  /// Bytes with a uint32 (or `prefix` bytes) length prefix.
  std::pair<const std::uint8_t*, std::size_t> bytes(std::size_t prefix, const char* field) {
    const std::uint64_t n = uint(prefix, field);
    need(n, field);
    const std::uint8_t* p = data_ + pos_;
    pos_ += n;
    return {p, static_cast<std::size_t>(n)};
  }
  void skip(std::size_t n, const char* field) {
    need(n, field);
    pos_ += n;
  }
  const std::uint8_t* here() const { return data_ + pos_; }
  std::size_t left() const { return size_ - pos_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  std::string where_;
};

struct Channel {
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string encoding;
  std::size_t topic_index = 0;
};

struct Schema {
  std::string name;
  std::string encoding;
  std::string data;
};

class McapStorage final : public MessageStorage {
 public:
  explicit McapStorage(std::string path) : path_(std::move(path)) {
    std::error_code ec;
    size_ = std::filesystem::file_size(path_, ec);
    if (ec) throw Error(path_ + ": cannot read the file size: " + ec.message());
    in_.open(path_, std::ios::binary);
    if (!in_) throw Error(path_ + ": cannot open the file for reading");
    if (size_ < kMcapMagicSize + kRecordHeader) {
      throw Error(path_ + ": truncated MCAP file (" + std::to_string(size_) + " bytes)");
    }
    const bool have_summary = readSummary();
    // Without statistics the file is read once to list its channels and count messages.
    if (!have_summary || !counts_known_) {
      select({});
      RawMessage m;
      counting_ = true;
      std::vector<std::int64_t> counts;
      while (next(m)) {
        if (counts.size() < topics_.size()) counts.resize(topics_.size(), 0);
        ++counts[m.topic];
        begin_ns_ = have_time_ ? std::min(begin_ns_, m.log_time_ns) : m.log_time_ns;
        end_ns_ = have_time_ ? std::max(end_ns_, m.log_time_ns) : m.log_time_ns;
        have_time_ = true;
      }
      counting_ = false;
      counts.resize(topics_.size(), 0);
      for (std::size_t t = 0; t < topics_.size(); ++t) topics_[t].count = counts[t];
      if (!cut_at_.empty()) {
        logWarning(path_ + ": the file is cut short (" + cut_at_ +
                   "); the complete records before it are read");
      }
    }
  }

  const std::vector<StorageTopic>& topics() const override { return topics_; }

  void select(const std::vector<bool>& wanted) override {
    wanted_ = wanted;
    in_.clear();
    in_.seekg(0);
    pos_ = 0;
    crc_ = 0;
    chunk_.clear();
    chunk_pos_ = 0;
    done_ = false;
    compressions_.clear();
    std::uint8_t magic[kMcapMagicSize];
    readExact(magic, kMcapMagicSize, "the magic");
    if (std::memcmp(magic, kMcapMagic, kMcapMagicSize) != 0) {
      throw Error(path_ + ": not an MCAP file (no magic 0x89 MCAP0 at byte 0)");
    }
  }

  bool next(RawMessage& out) override {
    while (!done_) {
      if (chunk_pos_ < chunk_.size()) {
        if (readChunkRecord(out)) return true;
        continue;
      }
      if (readDataRecord(out)) return true;
    }
    return false;
  }

  double progress() const override {
    return size_ > 0 ? std::min(1.0, static_cast<double>(pos_) / static_cast<double>(size_)) : 1.0;
  }
  std::int64_t beginNs() const override { return begin_ns_; }
  std::int64_t endNs() const override { return end_ns_; }
  std::uint64_t sizeBytes() const override { return size_; }

  std::vector<std::pair<std::string, std::string>> properties() const override {
    std::string compression;
    std::int64_t chunks = 0;
    for (const auto& [name, count] : compressions_) {
      chunks += count;
      compression += (compression.empty() ? "" : ", ") + name + " " + std::to_string(count);
    }
    return {{"storage", "MCAP (profile '" + profile_ + "', library '" + library_ + "')"},
            {"chunks", std::to_string(chunk_count_known_ ? chunk_count_ : chunks)},
            {"chunk compression", compression.empty() ? "none seen" : compression},
            {"summary section", summary_ ? "yes" : "no"}};
  }

 private:
  // --- file access: every byte of the data section goes through readExact (for its CRC)

  void readExact(void* dst, std::size_t n, const std::string& what) {
    in_.read(static_cast<char*>(dst), static_cast<std::streamsize>(n));
    if (static_cast<std::size_t>(in_.gcount()) != n) {
      throw Error(path_ + ": cannot read " + what + " at byte " + std::to_string(pos_));
    }
    crc_ = crc32Of(crc_, static_cast<const std::uint8_t*>(dst), n);
    pos_ += n;
  }

  std::string at(std::uint64_t offset) const { return path_ + ": byte " + std::to_string(offset); }

  /// Reads the next record of the data section; true when it delivered a message.
  bool readDataRecord(RawMessage& out) {
    const std::uint64_t start = pos_;
    if (size_ - pos_ < kRecordHeader) {
      cutShort(start, "inside a record header");
      return false;
    }
    const std::uint32_t crc_before = crc_;
    std::uint8_t head[kRecordHeader];
    readExact(head, kRecordHeader, "a record header");
    const std::uint8_t op = head[0];
    std::uint64_t length = 0;
    for (int k = 0; k < 8; ++k) length |= std::uint64_t{head[1 + k]} << (8 * k);
    if (op == 0) throw Error(at(start) + ": invalid record opcode 0x00 (damaged file?)");
    if (length > size_ - pos_) {
      cutShort(start, std::string("inside a ") + opcodeName(op) + " record of " +
                          std::to_string(length) + " bytes");
      return false;
    }
    if (op == kDataEnd) {
      record_.resize(length);
      in_.read(reinterpret_cast<char*>(record_.data()), static_cast<std::streamsize>(length));
      pos_ += length;
      Fields f(record_.data(), record_.size(), at(start) + " (Data End)");
      const std::uint32_t expected = f.u32("data_section_crc");
      if (expected != 0 && expected != crc_before) {
        throw Error(at(start) + ": data section CRC mismatch (Data End says " +
                    std::to_string(expected) + ", the bytes give " + std::to_string(crc_before) +
                    "): the file is damaged");
      }
      done_ = true;
      return false;
    }
    if (op == kFooter) {  // no Data End record (allowed for older writers)
      done_ = true;
      return false;
    }
    record_.resize(length);
    readExact(record_.data(), length, std::string("a ") + opcodeName(op) + " record");
    if (op == kHeader) {
      if (start != kMcapMagicSize) throw Error(at(start) + ": a second Header record");
      Fields f(record_.data(), record_.size(), at(start) + " (Header)");
      profile_ = f.string("profile");
      library_ = f.string("library");
      return false;
    }
    if (start == kMcapMagicSize) throw Error(at(start) + ": the first record is not a Header");
    return handleRecord(op, record_.data(), record_.size(), start, false, out);
  }

  /// Schema, Channel, Message (and Chunk in the data section).
  bool handleRecord(std::uint8_t op, const std::uint8_t* data, std::size_t size,
                    std::uint64_t offset, bool in_chunk, RawMessage& out) {
    const std::string where =
        at(offset) +
        (in_chunk ? " of the chunk at byte " + std::to_string(chunk_offset_) : std::string()) +
        " (" + opcodeName(op) + ")";
    switch (op) {
      case kSchema:
        readSchema(Fields(data, size, where));
        return false;
      case kChannel:
        readChannel(Fields(data, size, where), where);
        return false;
      case kMessage: {
        Fields f(data, size, where);
        const std::uint16_t channel_id = f.u16("channel_id");
        f.u32("sequence");
        const std::uint64_t log_time = f.u64("log_time");
        f.u64("publish_time");
        const auto it = channels_.find(channel_id);
        if (it == channels_.end()) {
          throw Error(where + ": message on channel " + std::to_string(channel_id) +
                      ", which no Channel record defines before it");
        }
        const std::size_t topic = it->second.topic_index;
        if (counting_) {
          out.topic = topic;
          out.log_time_ns = static_cast<std::int64_t>(log_time);
          out.data.clear();
          return true;
        }
        if (!wanted_.empty() && (topic >= wanted_.size() || !wanted_[topic])) return false;
        out.topic = topic;
        out.log_time_ns = static_cast<std::int64_t>(log_time);
        out.data.assign(f.here(), f.here() + f.left());
        return true;
      }
      case kChunk:
        if (in_chunk) throw Error(where + ": a chunk inside a chunk");
        readChunk(Fields(data, size, where), offset, where);
        return false;
      default:
        return false;  // indexes, attachments, metadata, statistics: not needed
    }
  }

  void readSchema(Fields f) {
    const std::uint16_t id = f.u16("id");
    Schema s;
    s.name = f.string("name");
    s.encoding = f.string("encoding");
    const auto [p, n] = f.bytes(4, "data");
    s.data.assign(reinterpret_cast<const char*>(p), n);
    if (id != 0) schemas_[id] = std::move(s);
  }

  void readChannel(Fields f, const std::string& where) {
    const std::uint16_t id = f.u16("id");
    Channel c;
    c.schema_id = f.u16("schema_id");
    c.topic = f.string("topic");
    c.encoding = f.string("message_encoding");
    if (channels_.count(id) != 0) return;  // repeated (summary or chunks)
    std::string type = "(no schema)";
    std::string definition;
    if (c.schema_id != 0) {
      const auto s = schemas_.find(c.schema_id);
      if (s == schemas_.end()) {
        throw Error(where + ": channel " + std::to_string(id) + " (" + c.topic +
                    ") refers to schema " + std::to_string(c.schema_id) +
                    ", which the file does not define before it");
      }
      type = s->second.name;
      definition = s->second.data;
    }
    const auto known = topic_by_channel_key_.find(c.topic + '\n' + type + '\n' + c.encoding);
    if (known != topic_by_channel_key_.end()) {
      c.topic_index = known->second;
    } else {
      c.topic_index = topics_.size();
      topic_by_channel_key_[c.topic + '\n' + type + '\n' + c.encoding] = c.topic_index;
      topics_.push_back(StorageTopic{c.topic, type, c.encoding, definition, 0});
    }
    channels_.emplace(id, std::move(c));
  }

  void readChunk(Fields f, std::uint64_t offset, const std::string& where) {
    f.u64("message_start_time");
    f.u64("message_end_time");
    const std::uint64_t uncompressed_size = f.u64("uncompressed_size");
    const std::uint32_t expected_crc = f.u32("uncompressed_crc");
    const std::string compression = f.string("compression");
    const auto [p, n] = f.bytes(8, "records");
    if (uncompressed_size > kMaxChunkBytes) {
      throw Error(where + ": chunk claims " + std::to_string(uncompressed_size) +
                  " uncompressed bytes (more than 4 GiB: damaged?)");
    }
    ++compressions_[compression.empty() ? "none" : compression];
    // Neither codec can expand a few bytes into gigabytes: a zstd block of 4 bytes (an RLE
    // block) gives at most 128 KiB, an lz4 sequence at most about 255 bytes per input byte.
    // A claim beyond that is damage, refused before allocating.
    const std::uint64_t most = compression == "zstd"  ? (n / 4 + 1) * (128ULL << 10)
                               : compression == "lz4" ? n * 256ULL + (64ULL << 10)
                                                      : uncompressed_size;
    if (uncompressed_size > most) {
      throw Error(where + ": " + compression + " chunk of " + std::to_string(n) +
                  " bytes claims " + std::to_string(uncompressed_size) +
                  " uncompressed bytes, more than " + compression +
                  " can expand to: the file is damaged");
    }
    if (compression.empty() && n != uncompressed_size) {  // checked before allocating
      throw Error(where + ": uncompressed chunk of " + std::to_string(n) +
                  " bytes but uncompressed_size " + std::to_string(uncompressed_size));
    }
    chunk_.resize(static_cast<std::size_t>(uncompressed_size));
    if (compression.empty()) {
      if (n > 0) std::memcpy(chunk_.data(), p, n);  // (an empty chunk_ has no data())
    } else if (compression == "zstd") {
      const std::size_t got = ZSTD_decompress(chunk_.data(), chunk_.size(), p, n);
      if (ZSTD_isError(got) || got != uncompressed_size) {
        throw Error(where + ": cannot decompress the zstd chunk (" +
                    (ZSTD_isError(got) ? std::string(ZSTD_getErrorName(got))
                                       : std::to_string(got) + " bytes instead of " +
                                             std::to_string(uncompressed_size)) +
                    "): the file is damaged");
      }
    } else if (compression == "lz4") {
      lz4Decompress(p, n, where);
    } else {
      throw Error(where + ": unknown chunk compression '" + compression +
                  "' (Storey reads none, zstd and lz4)");
    }
    if (expected_crc != 0) {
      const std::uint32_t crc = crc32Of(0, chunk_.data(), chunk_.size());
      if (crc != expected_crc) {
        throw Error(where + ": chunk CRC mismatch (the chunk says " + std::to_string(expected_crc) +
                    ", its records give " + std::to_string(crc) + "): the file is damaged");
      }
    }
    chunk_pos_ = 0;
    chunk_offset_ = offset;
  }

  void lz4Decompress(const std::uint8_t* src, std::size_t n, const std::string& where) {
    LZ4F_dctx* ctx = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) {
      throw Error(where + ": cannot create an lz4 decompression context");
    }
    std::size_t in_done = 0, out_done = 0;
    std::size_t hint = 1;
    while (hint != 0 && in_done < n) {
      std::size_t dst_size = chunk_.size() - out_done;
      std::size_t src_size = n - in_done;
      hint = LZ4F_decompress(ctx, chunk_.data() + out_done, &dst_size, src + in_done, &src_size,
                             nullptr);
      if (LZ4F_isError(hint)) {
        const std::string message = LZ4F_getErrorName(hint);
        LZ4F_freeDecompressionContext(ctx);
        throw Error(where + ": cannot decompress the lz4 chunk (" + message +
                    "): the file is damaged");
      }
      in_done += src_size;
      out_done += dst_size;
      if (src_size == 0 && dst_size == 0) break;
    }
    LZ4F_freeDecompressionContext(ctx);
    if (out_done != chunk_.size() || hint != 0) {
      throw Error(where + ": the lz4 chunk decompresses to " + std::to_string(out_done) +
                  " bytes, not " + std::to_string(chunk_.size()) + ": the file is damaged");
    }
  }

  /// Reads the next record inside the current chunk; true when it delivered a message.
  bool readChunkRecord(RawMessage& out) {
    const std::size_t start = chunk_pos_;
    const std::string where =
        at(chunk_offset_) + " (chunk), record at byte " + std::to_string(start) + " of its records";
    if (chunk_.size() - start < kRecordHeader) {
      throw Error(where + ": the chunk ends inside a record header");
    }
    const std::uint8_t op = chunk_[start];
    std::uint64_t length = 0;
    for (int k = 0; k < 8; ++k) length |= std::uint64_t{chunk_[start + 1 + k]} << (8 * k);
    if (length > chunk_.size() - start - kRecordHeader) {
      throw Error(where + ": a " + opcodeName(op) + " record of " + std::to_string(length) +
                  " bytes runs past the end of the chunk");
    }
    chunk_pos_ = start + kRecordHeader + static_cast<std::size_t>(length);
    const bool delivered = handleRecord(op, chunk_.data() + start + kRecordHeader,
                                        static_cast<std::size_t>(length), start, true, out);
    if (chunk_pos_ >= chunk_.size()) {
      chunk_.clear();
      chunk_pos_ = 0;
    }
    return delivered;
  }

  void cutShort(std::uint64_t offset, const std::string& what) {
    cut_at_ = "it ends at byte " + std::to_string(size_) + ", " + what + " starting at byte " +
              std::to_string(offset);
    done_ = true;
  }

  /// Reads the footer and the summary section when the file ends with the
  /// magic; false when it has none (or no summary).
  bool readSummary() {
    const std::uint64_t footer_size = kRecordHeader + kFooterContent;
    if (size_ < 2 * kMcapMagicSize + footer_size) return false;
    std::vector<std::uint8_t> tail(footer_size + kMcapMagicSize);
    in_.seekg(static_cast<std::streamoff>(size_ - tail.size()));
    in_.read(reinterpret_cast<char*>(tail.data()), static_cast<std::streamsize>(tail.size()));
    if (!in_) return false;
    if (std::memcmp(tail.data() + footer_size, kMcapMagic, kMcapMagicSize) != 0) return false;
    const std::uint64_t footer_pos = size_ - tail.size();
    if (tail[0] != kFooter) {
      throw Error(at(footer_pos) + ": the file ends with the MCAP magic but no Footer record");
    }
    Fields f(tail.data() + kRecordHeader, kFooterContent, at(footer_pos) + " (Footer)");
    const std::uint64_t summary_start = f.u64("summary_start");
    const std::uint64_t summary_offset_start = f.u64("summary_offset_start");
    const std::uint32_t summary_crc = f.u32("summary_crc");
    (void)summary_offset_start;
    if (summary_start == 0) return false;
    if (summary_start < kMcapMagicSize || summary_start > footer_pos) {
      throw Error(at(footer_pos) + ": Footer's summary_start " + std::to_string(summary_start) +
                  " lies outside the file");
    }
    std::vector<std::uint8_t> summary(static_cast<std::size_t>(footer_pos - summary_start));
    in_.seekg(static_cast<std::streamoff>(summary_start));
    in_.read(reinterpret_cast<char*>(summary.data()), static_cast<std::streamsize>(summary.size()));
    if (!in_) throw Error(at(summary_start) + ": cannot read the summary section");
    if (summary_crc != 0) {
      std::uint32_t crc = crc32Of(0, summary.data(), summary.size());
      crc = crc32Of(crc, tail.data(), kRecordHeader + 16);
      if (crc != summary_crc) {
        throw Error(at(summary_start) + ": summary section CRC mismatch (the Footer says " +
                    std::to_string(summary_crc) + ", the bytes give " + std::to_string(crc) +
                    "): the file is damaged");
      }
    }
    std::map<std::uint16_t, std::uint64_t> counts;
    std::size_t pos = 0;
    RawMessage unused;
    while (pos < summary.size()) {
      const std::uint64_t offset = summary_start + pos;
      if (summary.size() - pos < kRecordHeader) {
        throw Error(at(offset) + ": the summary section ends inside a record header");
      }
      const std::uint8_t op = summary[pos];
      std::uint64_t length = 0;
      for (int k = 0; k < 8; ++k) length |= std::uint64_t{summary[pos + 1 + k]} << (8 * k);
      if (length > summary.size() - pos - kRecordHeader) {
        throw Error(at(offset) + ": a " + std::string(opcodeName(op)) +
                    " record runs past the summary section");
      }
      const std::uint8_t* content = summary.data() + pos + kRecordHeader;
      const std::string where = at(offset) + " (" + opcodeName(op) + ")";
      if (op == kSchema) readSchema(Fields(content, length, where));
      if (op == kChannel) readChannel(Fields(content, length, where), where);
      if (op == kStatistics) {
        Fields s(content, length, where);
        s.u64("message_count");
        s.u16("schema_count");
        s.u32("channel_count");
        s.u32("attachment_count");
        s.u32("metadata_count");
        chunk_count_ = s.u32("chunk_count");
        chunk_count_known_ = true;
        begin_ns_ = static_cast<std::int64_t>(s.u64("message_start_time"));
        end_ns_ = static_cast<std::int64_t>(s.u64("message_end_time"));
        have_time_ = true;
        const std::uint32_t map_bytes = s.u32("channel_message_counts");
        Fields m(s.here(), std::min<std::size_t>(map_bytes, s.left()), where);
        s.skip(map_bytes, "channel_message_counts");
        while (m.left() > 0) {
          const std::uint16_t channel = m.u16("channel_message_counts");
          counts[channel] = m.u64("channel_message_counts");
        }
        counts_known_ = !counts.empty();
      }
      pos += kRecordHeader + static_cast<std::size_t>(length);
    }
    summary_ = true;
    for (const auto& [channel, count] : counts) {
      const auto it = channels_.find(channel);
      if (it == channels_.end()) {
        throw Error(at(summary_start) + ": the statistics count messages of channel " +
                    std::to_string(channel) + ", which the summary does not define");
      }
      topics_[it->second.topic_index].count += static_cast<std::int64_t>(count);
    }
    return true;
  }

  std::string path_;
  std::uint64_t size_ = 0;
  std::ifstream in_;
  std::uint64_t pos_ = 0;
  std::uint32_t crc_ = 0;  ///< of the bytes read since the start of the file
  std::string profile_, library_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::map<std::string, std::size_t> topic_by_channel_key_;
  std::vector<StorageTopic> topics_;
  std::vector<bool> wanted_;
  std::vector<std::uint8_t> record_;
  std::vector<std::uint8_t> chunk_;  ///< records of the current chunk, decompressed
  std::size_t chunk_pos_ = 0;
  std::uint64_t chunk_offset_ = 0;
  std::map<std::string, std::int64_t> compressions_;
  std::uint32_t chunk_count_ = 0;
  bool chunk_count_known_ = false;
  bool summary_ = false;
  bool counts_known_ = false;
  bool counting_ = false;
  bool done_ = false;
  bool have_time_ = false;
  std::int64_t begin_ns_ = 0, end_ns_ = 0;
  std::string cut_at_;
};

}  // namespace

bool isMcapMagic(const std::string& head) {
  return head.size() >= kMcapMagicSize && std::memcmp(head.data(), kMcapMagic, kMcapMagicSize) == 0;
}

std::unique_ptr<MessageStorage> openMcapStorage(const std::string& path) {
  return std::make_unique<McapStorage>(path);
}

}  // namespace storey
