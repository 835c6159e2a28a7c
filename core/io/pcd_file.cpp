#include "io/pcd_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/error.h"

namespace storey {
namespace {

template <class T>
bool inRangeOf(double v) {  // false for NaN
  return v >= static_cast<double>(std::numeric_limits<T>::lowest()) &&
         v <= static_cast<double>(std::numeric_limits<T>::max());
}

/// Whether an ascii value converts to a field of `datatype` without overflow
/// (a conversion out of range is undefined): integers in their range, float32
/// within its range or not finite (NaN, inf), float64 and 64-bit integers any.
bool fitsDatatype(double v, std::uint8_t datatype) {
  switch (datatype) {
    case 1:
      return inRangeOf<std::int8_t>(v);
    case 2:
      return inRangeOf<std::uint8_t>(v);
    case 3:
      return inRangeOf<std::int16_t>(v);
    case 4:
      return inRangeOf<std::uint16_t>(v);
    case 5:
      return inRangeOf<std::int32_t>(v);
    case 6:
      return inRangeOf<std::uint32_t>(v);
    case 7:
      return !std::isfinite(v) || inRangeOf<float>(v);
    default:
      return true;
  }
}

std::uint8_t datatypeOf(char type, int size) {
  switch (type) {
    case 'F': return size == 4 ? 7 : size == 8 ? 8 : 0;
    case 'U': return size == 1 ? 2 : size == 2 ? 4 : size == 4 ? 6 : size == 8 ? 200 : 0;
    case 'I': return size == 1 ? 1 : size == 2 ? 3 : size == 4 ? 5 : size == 8 ? 201 : 0;
  }
  return 0;
}
constexpr std::uint8_t kU64 = 200;  // converted to float64 after reading
constexpr std::uint8_t kI64 = 201;

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

/// Parses the header from `in`; `raw_sizes` receives each field's element size.
PcdHeader parseHeader(std::istream& in, const std::string& path, std::vector<int>& sizes,
                      std::vector<char>& types, std::vector<int>& counts) {
  PcdHeader h;
  std::vector<std::string> names;
  std::string line;
  int line_number = 0;
  bool have_points = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const auto w = words(line);
    if (w.empty()) continue;
    const std::string& key = w[0];
    auto fail = [&](const std::string& what) {
      throw Error(path + ": PCD header line " + std::to_string(line_number) + " ('" + line + "'): " + what);
    };
    try {
      if (key == "VERSION") {
        h.version = w.size() > 1 ? w[1] : "";
      } else if (key == "FIELDS" || key == "COLUMNS") {
        names.assign(w.begin() + 1, w.end());
      } else if (key == "SIZE") {
        sizes.clear();
        for (std::size_t i = 1; i < w.size(); ++i) sizes.push_back(std::stoi(w[i]));
      } else if (key == "TYPE") {
        types.clear();
        for (std::size_t i = 1; i < w.size(); ++i) types.push_back(w[i].empty() ? '?' : w[i][0]);
      } else if (key == "COUNT") {
        counts.clear();
        for (std::size_t i = 1; i < w.size(); ++i) counts.push_back(std::stoi(w[i]));
      } else if (key == "WIDTH" || key == "HEIGHT") {
        // stoull would wrap a negative count; a count beyond 32 bits is no PCD's.
        const std::uint64_t v = w.at(1)[0] == '-' ? ~0ULL : std::stoull(w.at(1));
        if (v > 0xFFFFFFFFULL) fail(key + " must be a count of points (0 to 2^32-1)");
        (key == "WIDTH" ? h.width : h.height) = static_cast<std::uint32_t>(v);
      } else if (key == "POINTS") {
        if (w.at(1)[0] == '-') fail("a negative number of points");  // stoull would wrap it
        h.points = std::stoull(w.at(1));
        have_points = true;
      } else if (key == "VIEWPOINT") {
        // ignored: the scan is in the sensor frame
      } else if (key == "DATA") {
        h.data = w.size() > 1 ? w[1] : "";
        if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed") {
          fail("DATA must be ascii, binary or binary_compressed");
        }
        h.data_offset = static_cast<std::size_t>(in.tellg());
        break;
      } else {
        fail("unknown PCD header keyword '" + key + "'");
      }
    } catch (const Error&) {
      throw;
    } catch (const std::exception&) {
      fail("expected numbers");
    }
  }
  if (h.data.empty()) throw Error(path + ": not a PCD file (no DATA line in the header)");
  if (names.empty()) throw Error(path + ": PCD header has no FIELDS line");
  if (counts.empty()) counts.assign(names.size(), 1);
  if (sizes.size() != names.size() || types.size() != names.size() || counts.size() != names.size()) {
    throw Error(path + ": PCD header: FIELDS, SIZE, TYPE and COUNT have different lengths");
  }
  if (!have_points) h.points = static_cast<std::uint64_t>(h.width) * h.height;
  std::uint32_t offset = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    PointFieldDesc f;
    f.name = names[i];
    f.offset = offset;
    f.datatype = datatypeOf(types[i], sizes[i]);
    f.count = static_cast<std::uint32_t>(std::max(1, counts[i]));
    if (f.datatype == 0) {
      throw Error(path + ": PCD field '" + f.name + "' has unsupported TYPE " + types[i] + " SIZE " +
                  std::to_string(sizes[i]));
    }
    // A point of more than 16 MiB is no PCD's (the widest PCL descriptors are a
    // few kB); the bound also keeps the 32-bit offsets from wrapping.
    const std::uint64_t end = offset + static_cast<std::uint64_t>(sizes[i]) * f.count;
    if (end > (std::uint64_t{1} << 24)) {
      throw Error(path + ": PCD header: a point of " + std::to_string(end) +
                  " bytes or more (field '" + f.name + "' COUNT " + std::to_string(f.count) +
                  "); at most 16 MiB a point");
    }
    offset = static_cast<std::uint32_t>(end);
    h.fields.push_back(f);
  }
  h.point_step = offset;
  return h;
}

void convertInt64Fields(PcdHeader& h, std::vector<std::uint8_t>& bytes) {
  for (auto& f : h.fields) {
    if (f.datatype != kU64 && f.datatype != kI64) continue;
    for (std::uint64_t p = 0; p < h.points; ++p) {
      for (std::uint32_t k = 0; k < f.count; ++k) {
        std::uint8_t* at = bytes.data() + p * h.point_step + f.offset + 8 * k;
        double value;
        if (f.datatype == kU64) {
          std::uint64_t v;
          std::memcpy(&v, at, 8);
          value = static_cast<double>(v);
        } else {
          std::int64_t v;
          std::memcpy(&v, at, 8);
          value = static_cast<double>(v);
        }
        std::memcpy(at, &value, 8);
      }
    }
    f.datatype = 8;
  }
}

int elementSize(const PointFieldDesc& f) {
  if (f.datatype == kU64 || f.datatype == kI64) return 8;
  return static_cast<int>(pointFieldTypeSize(f.datatype));
}

}  // namespace

bool looksLikePcd(const std::string& head) {
  return head.rfind("# .PCD", 0) == 0 || head.rfind("VERSION", 0) == 0 || head.rfind("FIELDS", 0) == 0;
}

bool lzfDecompress(const std::uint8_t* in, std::size_t in_size, std::uint8_t* out, std::size_t out_size) {
  std::size_t ip = 0, op = 0;
  while (ip < in_size) {
    const unsigned ctrl = in[ip++];
    if (ctrl < 32) {
      const std::size_t run = ctrl + 1;
      if (ip + run > in_size || op + run > out_size) return false;
      std::memcpy(out + op, in + ip, run);
      ip += run;
      op += run;
    } else {
      std::size_t length = ctrl >> 5;
      if (length == 7) {
        if (ip >= in_size) return false;
        length += in[ip++];
      }
      if (ip >= in_size) return false;
      const std::size_t back = ((ctrl & 0x1F) << 8) + in[ip++] + 1;
      length += 2;
      if (back > op || op + length > out_size) return false;
      for (std::size_t k = 0; k < length; ++k, ++op) out[op] = out[op - back];
    }
  }
  return op == out_size;
}

PointCloudView PcdCloud::view() const {
  PointCloudView v;
  v.fields = header.fields;
  v.height = 1;
  v.width = static_cast<std::uint32_t>(header.points);
  v.point_step = header.point_step;
  v.row_step = static_cast<std::uint32_t>(header.point_step * header.points);
  v.data = bytes.data();
  v.size = bytes.size();
  return v;
}

PcdHeader readPcdHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the PCD file");
  std::vector<int> sizes, counts;
  std::vector<char> types;
  return parseHeader(in, path, sizes, types, counts);
}

PcdCloud readPcd(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the PCD file");
  std::vector<int> sizes, counts;
  std::vector<char> types;
  PcdCloud cloud;
  cloud.header = parseHeader(in, path, sizes, types, counts);
  PcdHeader& h = cloud.header;
  // Before allocating: the header's points must fit in what the file holds after
  // the header (binary: point_step bytes a point; binary_compressed: LZF expands
  // at most about 100 times, 256 allowed; ascii: every value of every point takes
  // at least one character and a separator, so a 1-point header with COUNT
  // 100000000 cannot ask for 400 MB from a few bytes), so a damaged header asks
  // for no absurd memory (nor overflows the product).
  std::error_code ec;
  const std::uint64_t file_size = std::filesystem::file_size(path, ec);
  const std::uint64_t left = !ec && file_size > h.data_offset ? file_size - h.data_offset : 0;
  std::uint64_t values_per_point = 0;
  for (const auto& f : h.fields) values_per_point += f.count;
  const std::uint64_t factor = h.data == "binary_compressed" ? 256 : 1;  // left < 2^56: no overflow
  const std::uint64_t max_points =
      h.data == "ascii" ? (left / 2 + 1) / std::max<std::uint64_t>(values_per_point, 1)
                        : left * factor / std::max<std::uint64_t>(h.point_step, 1);
  if (h.points > max_points) {
    throw Error(path + ": PCD body truncated at byte " + std::to_string(h.data_offset + left) +
                ": " + std::to_string(h.points) + " points of " + std::to_string(h.point_step) +
                " bytes cannot be in the " + std::to_string(left) + " bytes after the header");
  }
  const std::size_t body = static_cast<std::size_t>(h.points * h.point_step);  // <= room
  cloud.bytes.assign(body, 0);
  if (h.data == "binary") {
    in.read(reinterpret_cast<char*>(cloud.bytes.data()), static_cast<std::streamsize>(body));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got != body) {
      throw Error(path + ": PCD body truncated at byte " + std::to_string(h.data_offset + got) +
                  ": " + std::to_string(h.points) + " points need " + std::to_string(body) +
                  " bytes, found " + std::to_string(got));
    }
  } else if (h.data == "binary_compressed") {
    std::uint32_t sizes_le[2] = {0, 0};
    in.read(reinterpret_cast<char*>(sizes_le), 8);
    if (in.gcount() != 8) throw Error(path + ": PCD binary_compressed body truncated (no size words)");
    if (sizes_le[1] != body) {
      throw Error(path + ": PCD binary_compressed: uncompressed size " + std::to_string(sizes_le[1]) +
                  " does not match " + std::to_string(h.points) + " points of " +
                  std::to_string(h.point_step) + " bytes");
    }
    if (sizes_le[0] > (left >= 8 ? left - 8 : 0)) {  // checked before allocating
      throw Error(path + ": PCD binary_compressed body truncated: " + std::to_string(sizes_le[0]) +
                  " compressed bytes announced, " + std::to_string(left >= 8 ? left - 8 : 0) +
                  " in the file");
    }
    std::vector<std::uint8_t> packed(sizes_le[0]);
    in.read(reinterpret_cast<char*>(packed.data()), static_cast<std::streamsize>(packed.size()));
    if (static_cast<std::size_t>(in.gcount()) != packed.size()) {
      throw Error(path + ": PCD binary_compressed body truncated");
    }
    std::vector<std::uint8_t> soa(body);
    if (body > 0 && !lzfDecompress(packed.data(), packed.size(), soa.data(), soa.size())) {
      throw Error(path + ": PCD binary_compressed body is corrupt (LZF)");
    }
    // Field-major (all points' first field, then the second...) to point-major.
    std::size_t at = 0;
    for (const auto& f : h.fields) {
      const std::size_t width = static_cast<std::size_t>(elementSize(f)) * f.count;
      for (std::uint64_t p = 0; p < h.points; ++p, at += width) {
        std::memcpy(cloud.bytes.data() + p * h.point_step + f.offset, soa.data() + at, width);
      }
    }
  } else {  // ascii
    std::string line;
    std::uint64_t p = 0;
    std::int64_t line_number = 0;
    while (p < h.points && std::getline(in, line)) {
      ++line_number;
      const auto w = words(line);
      if (w.empty()) continue;
      std::size_t k = 0;
      std::uint8_t* point = cloud.bytes.data() + p * h.point_step;
      for (const auto& f : h.fields) {
        for (std::uint32_t c = 0; c < f.count; ++c, ++k) {
          if (k >= w.size()) {
            throw Error(path + ": PCD ascii data line " + std::to_string(line_number) + " has " +
                        std::to_string(w.size()) + " values, expected more");
          }
          const double v = std::strtod(w[k].c_str(), nullptr);
          if (!fitsDatatype(v, f.datatype)) {
            throw Error(path + ": PCD ascii data line " + std::to_string(line_number) +
                        ": value '" + w[k] + "' of field '" + f.name + "' does not fit its type " +
                        pointFieldTypeName(f.datatype));
          }
          std::uint8_t* at = point + f.offset + c * elementSize(f);
          switch (f.datatype) {
            case 1: { auto x = static_cast<std::int8_t>(v); std::memcpy(at, &x, 1); break; }
            case 2: { auto x = static_cast<std::uint8_t>(v); std::memcpy(at, &x, 1); break; }
            case 3: { auto x = static_cast<std::int16_t>(v); std::memcpy(at, &x, 2); break; }
            case 4: { auto x = static_cast<std::uint16_t>(v); std::memcpy(at, &x, 2); break; }
            case 5: { auto x = static_cast<std::int32_t>(v); std::memcpy(at, &x, 4); break; }
            case 6: { auto x = static_cast<std::uint32_t>(v); std::memcpy(at, &x, 4); break; }
            case 7: { auto x = static_cast<float>(v); std::memcpy(at, &x, 4); break; }
            default: {  // float64 and 64-bit integers (read as double directly)
              std::memcpy(at, &v, 8);
            }
          }
        }
      }
      ++p;
    }
    if (p < h.points) {
      throw Error(path + ": PCD ascii data ends after " + std::to_string(p) + " of " +
                  std::to_string(h.points) + " points");
    }
    for (auto& f : h.fields) {
      if (f.datatype == kU64 || f.datatype == kI64) f.datatype = 8;  // already stored as double
    }
  }
  convertInt64Fields(h, cloud.bytes);
  return cloud;
}

}  // namespace storey
