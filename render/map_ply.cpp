// Streaming reader for our map PLY layout, keeping a display subsample.
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "render/run_data.h"

namespace storey::render {
namespace {

enum class Type { kChar, kUchar, kShort, kUshort, kInt, kUint, kFloat, kDouble };

bool parseType(const std::string& s, Type& t, int& size) {
  static const struct {
    const char* name;
    Type type;
    int size;
  } kTypes[] = {
      {"char", Type::kChar, 1},     {"int8", Type::kChar, 1},     {"uchar", Type::kUchar, 1},
      {"uint8", Type::kUchar, 1},   {"short", Type::kShort, 2},   {"int16", Type::kShort, 2},
      {"ushort", Type::kUshort, 2}, {"uint16", Type::kUshort, 2}, {"int", Type::kInt, 4},
      {"int32", Type::kInt, 4},     {"uint", Type::kUint, 4},     {"uint32", Type::kUint, 4},
      {"float", Type::kFloat, 4},   {"float32", Type::kFloat, 4}, {"double", Type::kDouble, 8},
      {"float64", Type::kDouble, 8}};
  for (const auto& k : kTypes) {
    if (s == k.name) {
      t = k.type;
      size = k.size;
      return true;
    }
  }
  return false;
}

double readValue(const char* p, Type t) {
  switch (t) {
    case Type::kChar: {
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return v;
    }
    case Type::kUchar: {
      std::uint8_t v;
      std::memcpy(&v, p, 1);
      return v;
    }
    case Type::kShort: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case Type::kUshort: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case Type::kInt: {
      std::int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case Type::kUint: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case Type::kFloat: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case Type::kDouble: {
      double v;
      std::memcpy(&v, p, 8);
      return v;
    }
  }
  return 0.0;
}

struct Field {
  int offset = -1;
  Type type = Type::kFloat;
};

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace

DisplaySubsample::DisplaySubsample(std::size_t points, std::size_t max_points)
    : all_(points <= max_points) {
  const double fraction =
      all_ ? 1.0 : static_cast<double>(max_points) / static_cast<double>(points);
  threshold_ = all_ ? ~0ull : static_cast<std::uint64_t>(fraction * 18446744073709551615.0);
  reserve_ = all_ ? points : max_points + max_points / 50 + 16;
}

bool DisplaySubsample::keeps(std::size_t index) const {
  return all_ || splitmix64(index) <= threshold_;
}

MapSample sampleMap(const MapCloud& map, std::size_t max_points) {
  MapSample out;
  out.file_points = map.size();
  const DisplaySubsample subsample(map.size(), max_points);
  out.positions.reserve(subsample.reserve());
  out.keyframe.reserve(subsample.reserve());
  out.storey.reserve(subsample.reserve());
  out.stairs.reserve(subsample.reserve());
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (!subsample.keeps(i) || !map.positions[i].allFinite()) continue;
    out.positions.push_back(map.positions[i]);
    out.keyframe.push_back(map.keyframe[i]);
    out.storey.push_back(map.storey[i]);
    out.stairs.push_back((map.flags[i] & kMapPointStairs) ? 1 : 0);
  }
  return out;
}

MapSample readMapSample(const std::string& path, std::size_t max_points) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the map");
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& what) -> void {
    throw Error(path + ": PLY header line " + std::to_string(line_no) + ": " + what);
  };
  std::getline(in, line);
  ++line_no;
  if (line != "ply") fail("not a PLY file (no 'ply' magic)");
  bool in_vertex = false, seen_vertex = false, format_ok = false;
  std::size_t vertices = 0;
  int record = 0;
  Field x, y, z, keyframe, storey, stairs;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ss(line);
    std::string word;
    ss >> word;
    if (word == "end_header") break;
    if (word == "comment" || word == "obj_info" || word.empty()) continue;
    if (word == "format") {
      std::string f;
      ss >> f;
      if (f != "binary_little_endian") fail("format '" + f + "' (the map is binary_little_endian)");
      format_ok = true;
    } else if (word == "element") {
      std::string name;
      ss >> name;
      if (seen_vertex && !in_vertex) continue;
      in_vertex = name == "vertex";
      if (!in_vertex && !seen_vertex)
        fail("element '" + name + "' before 'vertex' is not supported");
      if (in_vertex) {
        seen_vertex = true;
        if (!(ss >> vertices)) fail("vertex count missing");
      }
    } else if (word == "property" && in_vertex) {
      std::string type_name, name;
      ss >> type_name;
      if (type_name == "list") fail("list property in 'vertex' is not supported");
      ss >> name;
      Type t = Type::kFloat;
      int size = 0;
      if (!parseType(type_name, t, size)) fail("unknown property type '" + type_name + "'");
      const Field f{record, t};
      if (name == "x")
        x = f;
      else if (name == "y")
        y = f;
      else if (name == "z")
        z = f;
      else if (name == "keyframe")
        keyframe = f;
      else if (name == "storey")
        storey = f;
      else if (name == "stairs")
        stairs = f;
      record += size;
    } else if (word == "element" || word == "property") {
      continue;
    }
  }
  if (!format_ok) fail("no 'format' line");
  if (!seen_vertex) fail("no 'element vertex'");
  if (x.offset < 0 || y.offset < 0 || z.offset < 0) fail("vertex has no x, y, z");

  MapSample out;
  out.file_points = vertices;
  const DisplaySubsample subsample(vertices, max_points);
  out.positions.reserve(subsample.reserve());
  out.keyframe.reserve(subsample.reserve());
  out.storey.reserve(subsample.reserve());
  out.stairs.reserve(subsample.reserve());
  constexpr std::size_t kChunk = 65536;
  std::vector<char> buffer(kChunk * static_cast<std::size_t>(record));
  std::size_t done = 0;
  while (done < vertices) {
    const std::size_t n = std::min(kChunk, vertices - done);
    in.read(buffer.data(), static_cast<std::streamsize>(n * static_cast<std::size_t>(record)));
    if (static_cast<std::size_t>(in.gcount()) != n * static_cast<std::size_t>(record)) {
      throw Error(path + ": truncated: vertex " +
                  std::to_string(done + static_cast<std::size_t>(in.gcount()) / record) + " of " +
                  std::to_string(vertices) + " is incomplete");
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t index = done + i;
      if (!subsample.keeps(index)) continue;
      const char* r = buffer.data() + i * static_cast<std::size_t>(record);
      const Eigen::Vector3f p(static_cast<float>(readValue(r + x.offset, x.type)),
                              static_cast<float>(readValue(r + y.offset, y.type)),
                              static_cast<float>(readValue(r + z.offset, z.type)));
      if (!p.allFinite()) continue;
      out.positions.push_back(p);
      out.keyframe.push_back(keyframe.offset < 0 ? -1
                                                 : static_cast<std::int32_t>(readValue(
                                                       r + keyframe.offset, keyframe.type)));
      out.storey.push_back(
          storey.offset < 0 ? -1
                            : static_cast<std::int16_t>(readValue(r + storey.offset, storey.type)));
      out.stairs.push_back(
          stairs.offset < 0
              ? 0
              : static_cast<std::uint8_t>(readValue(r + stairs.offset, stairs.type) != 0.0));
    }
    done += n;
  }
  return out;
}

}  // namespace storey::render
