// The only file of sim that includes zstd, lz4 and zlib.
#include "sim/mcap_writer.h"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>

#include "common/error.h"

namespace storey::sim {
namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";

/// Little-endian record content builder.
struct Bytes {
  std::vector<std::uint8_t> b;
  void u8(std::uint8_t v) { b.push_back(v); }
  void u16(std::uint16_t v) { uint(v, 2); }
  void u32(std::uint32_t v) { uint(v, 4); }
  void u64(std::uint64_t v) { uint(v, 8); }
  void uint(std::uint64_t v, int n) {
    for (int k = 0; k < n; ++k) b.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    b.insert(b.end(), s.begin(), s.end());
  }
  void raw(const std::uint8_t* p, std::size_t n) { b.insert(b.end(), p, p + n); }
  void record(std::uint8_t op, const Bytes& content) {
    u8(op);
    u64(content.b.size());
    raw(content.b.data(), content.b.size());
  }
};

std::uint32_t crc(std::uint32_t c, const std::uint8_t* p, std::size_t n) {
  return static_cast<std::uint32_t>(::crc32(c, p, static_cast<uInt>(n)));
}

struct Topic {
  int id;
  std::string name, type, definition;
};

struct ChunkIndex {
  std::uint64_t start_ns, end_ns, offset, length, index_offset_start, index_length;
  std::map<std::uint16_t, std::uint64_t> index_offsets;
  std::uint64_t compressed, uncompressed;
};

class McapWriter final : public Ros2StorageWriter {
 public:
  McapWriter(std::string path, const McapWriterOptions& options)
      : path_(std::move(path)), options_(options) {
    file_ = std::fopen(path_.c_str(), "wb");
    if (file_ == nullptr) throw Error(path_ + ": cannot open for writing: " + std::strerror(errno));
    Bytes out;
    out.raw(reinterpret_cast<const std::uint8_t*>(kMagic), 8);
    Bytes header;
    header.str("ros2");
    header.str("storey");
    out.record(0x01, header);
    emit(out);
  }
  ~McapWriter() override {
    if (file_ != nullptr) std::fclose(file_);
  }

  void addTopic(int id, const std::string& name, const std::string& type,
                const std::string& definition) override {
    topics_.push_back(Topic{id, name, type, definition});
    Bytes out;
    writeSchemaAndChannel(out, topics_.back());
    emit(out);
  }

  void write(int id, std::int64_t log_time_ns, const std::vector<std::uint8_t>& data) override {
    Bytes m;
    m.u16(static_cast<std::uint16_t>(id));
    m.u32(sequence_[id]++);
    m.u64(static_cast<std::uint64_t>(log_time_ns));
    m.u64(static_cast<std::uint64_t>(log_time_ns));
    m.raw(data.data(), data.size());
    ++counts_[static_cast<std::uint16_t>(id)];
    ++messages_;
    const auto t = static_cast<std::uint64_t>(log_time_ns);
    start_ns_ = messages_ == 1 ? t : std::min(start_ns_, t);
    end_ns_ = std::max(end_ns_, t);
    if (!options_.chunked) {
      Bytes out;
      out.record(0x05, m);
      emit(out);
      return;
    }
    if (chunk_.b.empty()) chunk_start_ns_ = chunk_end_ns_ = t;
    chunk_start_ns_ = std::min(chunk_start_ns_, t);
    chunk_end_ns_ = std::max(chunk_end_ns_, t);
    chunk_index_[static_cast<std::uint16_t>(id)].push_back({t, chunk_.b.size()});
    chunk_.record(0x05, m);
    if (chunk_.b.size() >= options_.chunk_bytes) flushChunk();
  }

  void close() override {
    if (file_ == nullptr) return;
    flushChunk();
    Bytes data_end;
    data_end.u32(data_crc_);
    Bytes out;
    out.record(0x0F, data_end);
    emit(out);
    const std::uint64_t summary_start = options_.summary ? offset_ : 0;
    std::uint32_t summary_crc = 0;
    if (options_.summary) {
      Bytes summary;
      for (const auto& t : topics_) writeSchemaAndChannel(summary, t);
      Bytes stats;
      stats.u64(messages_);
      stats.u16(static_cast<std::uint16_t>(topics_.size()));
      stats.u32(static_cast<std::uint32_t>(topics_.size()));
      stats.u32(0);
      stats.u32(0);
      stats.u32(static_cast<std::uint32_t>(chunks_.size()));
      stats.u64(messages_ > 0 ? start_ns_ : 0);
      stats.u64(messages_ > 0 ? end_ns_ : 0);
      Bytes counts;
      for (const auto& [id, n] : counts_) {
        counts.u16(id);
        counts.u64(n);
      }
      stats.u32(static_cast<std::uint32_t>(counts.b.size()));
      stats.raw(counts.b.data(), counts.b.size());
      summary.record(0x0B, stats);
      for (const auto& c : chunks_) {
        Bytes ci;
        ci.u64(c.start_ns);
        ci.u64(c.end_ns);
        ci.u64(c.offset);
        ci.u64(c.length);
        Bytes offsets;
        for (const auto& [id, at] : c.index_offsets) {
          offsets.u16(id);
          offsets.u64(at);
        }
        ci.u32(static_cast<std::uint32_t>(offsets.b.size()));
        ci.raw(offsets.b.data(), offsets.b.size());
        ci.u64(c.index_length);
        ci.str(compressionName());
        ci.u64(c.compressed);
        ci.u64(c.uncompressed);
        summary.record(0x08, ci);
      }
      summary_crc = crc(0, summary.b.data(), summary.b.size());
      emit(summary);
    }
    Bytes footer;
    footer.u8(0x02);
    footer.u64(20);
    footer.u64(summary_start);
    footer.u64(0);
    if (options_.summary) summary_crc = crc(summary_crc, footer.b.data(), footer.b.size());
    footer.u32(summary_crc);
    footer.raw(reinterpret_cast<const std::uint8_t*>(kMagic), 8);
    emit(footer);
    const bool ok = std::fflush(file_) == 0;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!ok || !closed) throw Error(path_ + ": cannot write: " + std::strerror(errno));
  }

 private:
  std::string compressionName() const {
    switch (options_.compression) {
      case McapCompression::kZstd:
        return "zstd";
      case McapCompression::kLz4:
        return "lz4";
      case McapCompression::kNone:
        break;
    }
    return "";
  }

  static void writeSchemaAndChannel(Bytes& out, const Topic& t) {
    Bytes schema;
    schema.u16(static_cast<std::uint16_t>(t.id));
    schema.str(t.type);
    schema.str("ros2msg");
    schema.str(t.definition);
    out.record(0x03, schema);
    Bytes channel;
    channel.u16(static_cast<std::uint16_t>(t.id));
    channel.u16(static_cast<std::uint16_t>(t.id));
    channel.str(t.name);
    channel.str("cdr");
    channel.u32(0);  // metadata: empty map
    out.record(0x04, channel);
  }

  void emit(const Bytes& out) {
    if (std::fwrite(out.b.data(), 1, out.b.size(), file_) != out.b.size()) {
      throw Error(path_ + ": cannot write: " + std::strerror(errno));
    }
    data_crc_ = crc(data_crc_, out.b.data(), out.b.size());
    offset_ += out.b.size();
  }

  std::vector<std::uint8_t> compress(const std::vector<std::uint8_t>& in) const {
    std::vector<std::uint8_t> out;
    if (options_.compression == McapCompression::kZstd) {
      out.resize(ZSTD_compressBound(in.size()));
      const std::size_t n = ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3);
      if (ZSTD_isError(n)) throw Error(path_ + ": zstd: " + ZSTD_getErrorName(n));
      out.resize(n);
    } else if (options_.compression == McapCompression::kLz4) {
      out.resize(LZ4F_compressFrameBound(in.size(), nullptr));
      const std::size_t n =
          LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr);
      if (LZ4F_isError(n)) throw Error(path_ + ": lz4: " + LZ4F_getErrorName(n));
      out.resize(n);
    } else {
      out = in;
    }
    return out;
  }

  void flushChunk() {
    if (chunk_.b.empty()) return;
    const std::vector<std::uint8_t> records = compress(chunk_.b);
    Bytes content;
    content.u64(chunk_start_ns_);
    content.u64(chunk_end_ns_);
    content.u64(chunk_.b.size());
    content.u32(crc(0, chunk_.b.data(), chunk_.b.size()));
    content.str(compressionName());
    content.u64(records.size());
    content.raw(records.data(), records.size());
    Bytes out;
    out.record(0x06, content);
    ChunkIndex index{chunk_start_ns_, chunk_end_ns_,  offset_, out.b.size(), 0, 0, {},
                     records.size(),  chunk_.b.size()};
    emit(out);
    index.index_offset_start = offset_;
    for (const auto& [id, entries] : chunk_index_) {
      Bytes mi;
      mi.u16(id);
      mi.u32(static_cast<std::uint32_t>(entries.size() * 16));
      for (const auto& [t, at] : entries) {
        mi.u64(t);
        mi.u64(at);
      }
      Bytes rec;
      rec.record(0x07, mi);
      index.index_offsets[id] = offset_;
      emit(rec);
    }
    index.index_length = offset_ - index.index_offset_start;
    chunks_.push_back(index);
    chunk_.b.clear();
    chunk_index_.clear();
  }

  std::string path_;
  McapWriterOptions options_;
  std::FILE* file_ = nullptr;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;
  std::vector<Topic> topics_;
  std::map<int, std::uint32_t> sequence_;
  std::map<std::uint16_t, std::uint64_t> counts_;
  std::uint64_t messages_ = 0;
  std::uint64_t start_ns_ = 0, end_ns_ = 0;
  Bytes chunk_;
  std::uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::vector<ChunkIndex> chunks_;
};

}  // namespace

std::unique_ptr<Ros2StorageWriter> openMcapWriter(const std::string& path,
                                                  const McapWriterOptions& options) {
  return std::make_unique<McapWriter>(path, options);
}

}  // namespace storey::sim
