#include "eval/ply_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "common/error.h"

namespace storey::eval {
namespace {

enum class Format { kAscii, kBinaryLittle, kBinaryBig };
enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

std::size_t sizeOf(Type type) {
  switch (type) {
    case Type::kInt8:
    case Type::kUint8:
      return 1;
    case Type::kInt16:
    case Type::kUint16:
      return 2;
    case Type::kInt32:
    case Type::kUint32:
    case Type::kFloat32:
      return 4;
    case Type::kFloat64:
      return 8;
  }
  return 0;
}

bool parseType(const std::string& name, Type& type) {
  static const std::pair<const char*, Type> kNames[] = {
      {"char", Type::kInt8},      {"int8", Type::kInt8},       {"uchar", Type::kUint8},
      {"uint8", Type::kUint8},    {"short", Type::kInt16},     {"int16", Type::kInt16},
      {"ushort", Type::kUint16},  {"uint16", Type::kUint16},   {"int", Type::kInt32},
      {"int32", Type::kInt32},    {"uint", Type::kUint32},     {"uint32", Type::kUint32},
      {"float", Type::kFloat32},  {"float32", Type::kFloat32}, {"double", Type::kFloat64},
      {"float64", Type::kFloat64}};
  for (const auto& [text, t] : kNames) {
    if (name == text) {
      type = t;
      return true;
    }
  }
  return false;
}

struct Property {
  std::string name;
  Type type = Type::kFloat32;  ///< the value type (of the items for a list)
  bool is_list = false;
  Type count_type = Type::kUint8;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
  int find(const std::string& property) const {
    for (std::size_t i = 0; i < properties.size(); ++i)
      if (properties[i].name == property) return static_cast<int>(i);
    return -1;
  }
};

struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  const Element* find(const std::string& name) const {
    for (const Element& e : elements)
      if (e.name == name) return &e;
    return nullptr;
  }
};

Header readHeader(std::istream& in, const std::string& path) {
  Header header;
  std::string line;
  int line_number = 0;
  bool have_format = false;
  auto fail = [&](const std::string& what) -> Error {
    return Error(path + ": PLY header line " + std::to_string(line_number) + ": " + what);
  };
  while (true) {
    if (!std::getline(in, line)) {
      ++line_number;
      throw fail(line_number == 1 ? "empty file, expected 'ply'" : "file ends before 'end_header'");
    }
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_number == 1) {
      if (line != "ply") throw fail("not a PLY file (the first line is not 'ply')");
      continue;
    }
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") break;
    if (keyword == "format") {
      std::string format, version;
      words >> format >> version;
      if (format == "ascii")
        header.format = Format::kAscii;
      else if (format == "binary_little_endian")
        header.format = Format::kBinaryLittle;
      else if (format == "binary_big_endian")
        header.format = Format::kBinaryBig;
      else
        throw fail("unknown format '" + format +
                   "' (ascii, binary_little_endian or binary_big_endian)");
      if (version != "1.0") throw fail("unsupported format version '" + version + "' (1.0)");
      have_format = true;
    } else if (keyword == "element") {
      Element element;
      long long count = -1;
      if (!(words >> element.name >> count) || count < 0)
        throw fail("expected 'element NAME COUNT'");
      element.count = static_cast<std::size_t>(count);
      // The body is read by element name: a second 'vertex' with other
      // properties would be indexed with the first one's (found by fuzzing).
      if (header.find(element.name) != nullptr)
        throw fail("element '" + element.name + "' declared twice");
      header.elements.push_back(element);
    } else if (keyword == "property") {
      if (header.elements.empty()) throw fail("property before any element");
      Property property;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> property.name;
        property.is_list = true;
        if (!parseType(count_type, property.count_type))
          throw fail("unknown type '" + count_type + "'");
        if (property.count_type == Type::kFloat32 || property.count_type == Type::kFloat64)
          throw fail("a list count must be an integer type");
        if (!parseType(item_type, property.type)) throw fail("unknown type '" + item_type + "'");
      } else {
        words >> property.name;
        if (!parseType(type, property.type)) throw fail("unknown type '" + type + "'");
      }
      if (property.name.empty()) throw fail("property without a name");
      header.elements.back().properties.push_back(property);
    } else {
      throw fail("unknown keyword '" + keyword + "'");
    }
  }
  if (!have_format) throw Error(path + ": PLY header has no 'format' line");
  return header;
}

/// Reads the values of one record, property after property. Binary input is
/// buffered; ASCII input is whitespace-separated tokens.
class RecordReader {
 public:
  RecordReader(std::istream& in, Format format) : in_(in), format_(format) {}

  /// One scalar of `type` as double; false at the end of the data.
  bool value(Type type, double& out) {
    if (format_ == Format::kAscii) return asciiValue(type, out);
    unsigned char bytes[8];
    const std::size_t n = sizeOf(type);
    if (!take(bytes, n)) return false;
    if (format_ == Format::kBinaryBig) std::reverse(bytes, bytes + n);
    switch (type) {
      case Type::kInt8:
        out = static_cast<std::int8_t>(bytes[0]);
        break;
      case Type::kUint8:
        out = bytes[0];
        break;
      case Type::kInt16:
        out = load<std::int16_t>(bytes);
        break;
      case Type::kUint16:
        out = load<std::uint16_t>(bytes);
        break;
      case Type::kInt32:
        out = load<std::int32_t>(bytes);
        break;
      case Type::kUint32:
        out = load<std::uint32_t>(bytes);
        break;
      case Type::kFloat32:
        out = load<float>(bytes);
        break;
      case Type::kFloat64:
        out = load<double>(bytes);
        break;
    }
    return true;
  }

 private:
  template <typename T>
  static T load(const unsigned char* bytes) {
    T v;
    std::memcpy(&v, bytes, sizeof(T));  // host is little-endian (x86-64, aarch64)
    return v;
  }

  bool take(unsigned char* dst, std::size_t n) {
    if (end_ - pos_ < n) {
      std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
      end_ -= pos_;
      pos_ = 0;
      in_.read(reinterpret_cast<char*>(buffer_.data() + end_),
               static_cast<std::streamsize>(buffer_.size() - end_));
      end_ += static_cast<std::size_t>(in_.gcount());
      if (end_ < n) return false;
    }
    std::memcpy(dst, buffer_.data() + pos_, n);
    pos_ += n;
    return true;
  }

  bool asciiValue(Type type, double& out) {
    std::string token;
    if (!(in_ >> token)) return false;
    char* end = nullptr;
    out = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') return false;
    if (type != Type::kFloat32 && type != Type::kFloat64 && out != std::floor(out)) return false;
    return true;
  }

  std::istream& in_;
  Format format_;
  std::vector<unsigned char> buffer_ = std::vector<unsigned char>(1 << 20);
  std::size_t pos_ = 0, end_ = 0;
};

/// Calls on_record(record_index, scalars, lists) for every record of every
/// element; scalars[k] is property k's value (lists: their first item), lists[k]
/// the items of list property k (empty for scalars).
using RecordFn = std::function<void(const Element&, std::size_t, const std::vector<double>&,
                                    const std::vector<std::vector<double>>&)>;

void readBody(std::istream& in, const Header& header, const std::string& path,
              const RecordFn& on_record) {
  RecordReader reader(in, header.format);
  for (const Element& element : header.elements) {
    std::vector<double> scalars(element.properties.size(), 0.0);
    std::vector<std::vector<double>> lists(element.properties.size());
    for (std::size_t r = 0; r < element.count; ++r) {
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const Property& p = element.properties[k];
        auto fail = [&]() {
          return Error(path + ": PLY data truncated or malformed in element '" + element.name +
                       "' record " + std::to_string(r) + " of " + std::to_string(element.count) +
                       ", property '" + p.name + "'");
        };
        if (!p.is_list) {
          if (!reader.value(p.type, scalars[k])) throw fail();
          continue;
        }
        double count = 0.0;
        if (!reader.value(p.count_type, count) || count < 0.0 || count > 1e6) throw fail();
        lists[k].resize(static_cast<std::size_t>(count));
        for (double& item : lists[k])
          if (!reader.value(p.type, item)) throw fail();
        scalars[k] = lists[k].empty() ? 0.0 : lists[k].front();
      }
      on_record(element, r, scalars, lists);
    }
  }
}

/// How many records of `element` the rest of the file could hold at most
/// (binary: every scalar and list count; ASCII: a digit and a separator per
/// value), so that a corrupt count in the header reserves no absurd memory.
/// Reading still stops at the exact record where the data ends.
std::size_t reservableRecords(std::istream& in, const Header& header, const Element& element) {
  const std::streampos body = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streampos end = in.tellg();
  in.seekg(body);
  if (body < 0 || end < body) return 0;  // not seekable
  std::size_t record = 0;
  for (const Property& p : element.properties)
    record += header.format == Format::kAscii ? 2 : sizeOf(p.is_list ? p.count_type : p.type);
  const std::size_t available = static_cast<std::size_t>(end - body);
  return std::min(element.count, record > 0 ? available / record : 0);
}

std::ifstream openPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open PLY file");
  return in;
}

struct VertexProperties {
  int x = -1, y = -1, z = -1;
};

/// Index of the scalar vertex property `name` (storey::Error when it is missing or a list).
std::size_t scalarVertexProperty(const Element& vertex, const std::string& name,
                                 const std::string& path) {
  const int k = vertex.find(name);
  if (k < 0) throw Error(path + ": PLY element 'vertex' has no property '" + name + "'");
  if (vertex.properties[static_cast<std::size_t>(k)].is_list)
    throw Error(path + ": PLY vertex property '" + name + "' is a list, expected a scalar");
  return static_cast<std::size_t>(k);
}

VertexProperties vertexProperties(const Header& header, const std::string& path) {
  const Element* vertex = header.find("vertex");
  if (vertex == nullptr) throw Error(path + ": PLY file has no 'vertex' element");
  return VertexProperties{static_cast<int>(scalarVertexProperty(*vertex, "x", path)),
                          static_cast<int>(scalarVertexProperty(*vertex, "y", path)),
                          static_cast<int>(scalarVertexProperty(*vertex, "z", path))};
}

}  // namespace

PlyPoints readPlyPoints(const std::string& path) {
  std::ifstream in = openPly(path);
  const Header header = readHeader(in, path);
  const VertexProperties v = vertexProperties(header, path);
  PlyPoints points;
  points.positions.reserve(reservableRecords(in, header, *header.find("vertex")));
  readBody(in, header, path,
           [&](const Element& element, std::size_t, const std::vector<double>& s,
               const std::vector<std::vector<double>>&) {
             if (element.name != "vertex") return;
             const Eigen::Vector3d p(s[v.x], s[v.y], s[v.z]);
             if (p.allFinite())
               points.positions.push_back(p);
             else
               ++points.non_finite;
           });
  return points;
}

PlyVertexColumns readPlyVertexColumns(const std::string& path,
                                      const std::vector<std::string>& names) {
  std::ifstream in = openPly(path);
  const Header header = readHeader(in, path);
  const VertexProperties v = vertexProperties(header, path);
  const Element& vertex = *header.find("vertex");
  std::vector<std::size_t> properties;
  for (const std::string& name : names)
    properties.push_back(scalarVertexProperty(vertex, name, path));
  PlyVertexColumns out;
  const std::size_t n = reservableRecords(in, header, vertex);
  out.positions.reserve(n);
  out.columns.resize(names.size());
  for (std::vector<double>& column : out.columns) column.reserve(n);
  readBody(in, header, path,
           [&](const Element& element, std::size_t, const std::vector<double>& s,
               const std::vector<std::vector<double>>&) {
             if (element.name != "vertex") return;
             out.positions.emplace_back(s[v.x], s[v.y], s[v.z]);
             for (std::size_t c = 0; c < properties.size(); ++c)
               out.columns[c].push_back(s[properties[c]]);
           });
  return out;
}

PlyMesh readPlyMesh(const std::string& path, bool returning_only) {
  std::ifstream in = openPly(path);
  const Header header = readHeader(in, path);
  const VertexProperties v = vertexProperties(header, path);
  const Element* face = header.find("face");
  if (face == nullptr)
    throw Error(path + ": PLY file has no 'face' element (expected a triangle mesh)");
  int indices = face->find("vertex_indices");
  if (indices < 0) indices = face->find("vertex_index");
  if (indices < 0 || !face->properties[static_cast<std::size_t>(indices)].is_list)
    throw Error(path + ": PLY element 'face' has no list property 'vertex_indices'");
  const int returns = face->find("returns");
  const std::size_t vertex_count = header.find("vertex")->count;

  PlyMesh mesh;
  mesh.vertices.reserve(reservableRecords(in, header, *header.find("vertex")));
  mesh.triangles.reserve(reservableRecords(in, header, *face));
  std::vector<std::uint32_t> polygon;
  readBody(in, header, path,
           [&](const Element& element, std::size_t r, const std::vector<double>& s,
               const std::vector<std::vector<double>>& lists) {
             if (element.name == "vertex") {
               const Eigen::Vector3d p(s[v.x], s[v.y], s[v.z]);
               if (!p.allFinite())
                 throw Error(path + ": PLY vertex " + std::to_string(r) + " is not finite");
               mesh.vertices.push_back(p);
               return;
             }
             if (element.name != "face") return;
             ++mesh.faces_read;
             if (returning_only && returns >= 0 && s[static_cast<std::size_t>(returns)] == 0.0) {
               ++mesh.faces_not_returning;
               return;
             }
             const std::vector<double>& items = lists[static_cast<std::size_t>(indices)];
             polygon.clear();
             for (double index : items) {
               if (!(index >= 0.0 && index < static_cast<double>(vertex_count)))
                 throw Error(path + ": PLY face " + std::to_string(r) + " refers to vertex " +
                             std::to_string(static_cast<long long>(index)) + " of " +
                             std::to_string(vertex_count));
               polygon.push_back(static_cast<std::uint32_t>(index));
             }
             if (polygon.size() < 3) {
               ++mesh.faces_degenerate;
               return;
             }
             for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
               mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
           });
  return mesh;
}

}  // namespace storey::eval
