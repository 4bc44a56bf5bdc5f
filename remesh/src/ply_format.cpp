#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "binary_formats.hpp"
#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh::detail {
namespace {

enum class Encoding { Ascii, LittleEndian, BigEndian };

struct Property {
  std::string name;
  std::string type;        // scalar type, or the item type of a list
  std::string count_type;  // non-empty for a list
};

struct Element {
  std::string name;
  long count = 0;
  std::vector<Property> properties;
};

constexpr long kMaxElements = 200'000'000;

int type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

class PlyReader {
 public:
  explicit PlyReader(const std::filesystem::path& file) : file_(file), in_(file, std::ios::binary) {
    if (!in_) throw InputError(file.string() + ": cannot be opened for reading");
  }

  PolygonSoup read() {
    read_header();
    PolygonSoup soup;
    for (const Element& element : elements_) {
      const bool is_vertex = element.name == "vertex", is_face = element.name == "face";
      int ix = -1, iy = -1, iz = -1, iface = -1;
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const auto& p = element.properties[k];
        if (p.name == "x") ix = static_cast<int>(k);
        if (p.name == "y") iy = static_cast<int>(k);
        if (p.name == "z") iz = static_cast<int>(k);
        if (!p.count_type.empty() && (p.name == "vertex_indices" || p.name == "vertex_index")) iface = static_cast<int>(k);
      }
      if (is_vertex && (ix < 0 || iy < 0 || iz < 0)) fail("the vertex element has no x, y and z properties");
      if (is_face && iface < 0) fail("the face element has no vertex_indices list");
      std::vector<double> scalars(element.properties.size());
      std::vector<double> list;
      for (long i = 0; i < element.count; ++i) {
        std::vector<int> polygon;
        for (std::size_t k = 0; k < element.properties.size(); ++k) {
          const auto& p = element.properties[k];
          if (p.count_type.empty()) {
            scalars[k] = value(p.type, element.name, i);
          } else {
            const double n = value(p.count_type, element.name, i);
            if (!(n >= 0 && n <= 1000)) fail(element.name + " " + std::to_string(i) + " has a list of " + std::to_string(n) + " items");
            list.assign(static_cast<std::size_t>(n), 0.0);
            for (auto& item : list) item = value(p.type, element.name, i);
            if (static_cast<int>(k) == iface)
              for (double index : list) {
                if (!(index >= 0 && index < static_cast<double>(kMaxElements)) || index != std::floor(index))
                  fail(element.name + " " + std::to_string(i) + " has the invalid vertex index " + std::to_string(index));
                polygon.push_back(static_cast<int>(index));
              }
          }
        }
        if (is_vertex) soup.points.emplace_back(scalars[static_cast<std::size_t>(ix)], scalars[static_cast<std::size_t>(iy)],
                                                scalars[static_cast<std::size_t>(iz)]);
        if (is_face) soup.polygons.push_back(std::move(polygon));
      }
    }
    const long nv = static_cast<long>(soup.points.size());
    for (std::size_t f = 0; f < soup.polygons.size(); ++f)
      for (int index : soup.polygons[f])
        if (index < 0 || index >= nv)
          fail("face " + std::to_string(f) + " refers to vertex " + std::to_string(index) + ", out of range (the file has " +
               std::to_string(nv) + " vertices)");
    return soup;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_.string() + ": " + problem); }

  void read_header() {
    std::string line;
    if (!std::getline(in_, line) || line.substr(0, 3) != "ply") fail("not a PLY file (no 'ply' magic)");
    bool format_seen = false;
    while (true) {
      if (!std::getline(in_, line)) fail("truncated PLY header (no end_header)");
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find('\0') != std::string::npos) fail("binary data in the PLY header");
      std::istringstream words(line);
      std::string keyword;
      words >> keyword;
      if (keyword == "end_header") break;
      if (keyword == "format") {
        std::string encoding;
        words >> encoding;
        if (encoding == "ascii") encoding_ = Encoding::Ascii;
        else if (encoding == "binary_little_endian") encoding_ = Encoding::LittleEndian;
        else if (encoding == "binary_big_endian") encoding_ = Encoding::BigEndian;
        else fail("unknown PLY format '" + printable(encoding) + "'");
        format_seen = true;
      } else if (keyword == "element") {
        Element e;
        if (!(words >> e.name >> e.count) || e.count < 0 || e.count > kMaxElements) fail("bad element line '" + printable(line) + "'");
        elements_.push_back(e);
      } else if (keyword == "property") {
        if (elements_.empty()) fail("property before any element");
        Property p;
        std::string type;
        words >> type;
        if (type == "list") {
          words >> p.count_type >> p.type >> p.name;
          if (type_size(p.count_type) == 0 || type_size(p.type) == 0) fail("bad list property '" + printable(line) + "'");
        } else {
          p.type = type;
          words >> p.name;
          if (type_size(p.type) == 0) fail("unknown property type '" + printable(type) + "'");
        }
        elements_.back().properties.push_back(p);
      } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
        fail("unknown PLY header line '" + printable(line) + "'");
      }
    }
    if (!format_seen) fail("PLY header without a format line");
  }

  double value(const std::string& type, const std::string& element, long index) {
    if (encoding_ == Encoding::Ascii) {
      std::string token;
      if (!(in_ >> token)) fail("truncated: " + element + " " + std::to_string(index) + " is incomplete");
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') fail("'" + printable(token) + "' is not a number (" + element + " " + std::to_string(index) + ")");
      return v;
    }
    unsigned char bytes[8];
    const int size = type_size(type);
    if (!in_.read(reinterpret_cast<char*>(bytes), size))
      fail("truncated: " + element + " " + std::to_string(index) + " is incomplete");
    const bool swap = (encoding_ == Encoding::LittleEndian) != (std::endian::native == std::endian::little);
    if (swap) std::reverse(bytes, bytes + size);
    auto as = [&](auto v) {
      std::memcpy(&v, bytes, sizeof v);
      return static_cast<double>(v);
    };
    if (type == "char" || type == "int8") return as(std::int8_t{});
    if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
    if (type == "short" || type == "int16") return as(std::int16_t{});
    if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
    if (type == "int" || type == "int32") return as(std::int32_t{});
    if (type == "uint" || type == "uint32") return as(std::uint32_t{});
    if (type == "float" || type == "float32") return as(float{});
    return as(double{});
  }

  std::filesystem::path file_;
  std::ifstream in_;
  Encoding encoding_ = Encoding::Ascii;
  std::vector<Element> elements_;
};

}  // namespace

PolygonSoup read_ply(const std::filesystem::path& file) { return PlyReader(file).read(); }

bool write_ply(const TriMesh& mesh, const std::filesystem::path& file) {
  std::ofstream out(file, std::ios::binary);
  if (!out) return false;
  std::vector<int> number(mesh.n_vertices(), -1);
  int nv = 0, nf = 0;
  for (auto v : mesh.vertices()) number[static_cast<std::size_t>(v.idx())] = nv++;
  for ([[maybe_unused]] auto f : mesh.faces()) ++nf;
  out << "ply\nformat binary_little_endian 1.0\ncomment carbonmesh\nelement vertex " << nv
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << nf
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  static_assert(std::endian::native == std::endian::little, "write_ply assumes a little-endian machine");
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    const double xyz[3] = {p[0], p[1], p[2]};
    out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  for (auto f : mesh.faces()) {
    const std::uint8_t n = 3;
    out.write(reinterpret_cast<const char*>(&n), 1);
    for (auto v : mesh.fv_range(f)) {
      const std::int32_t index = number[static_cast<std::size_t>(v.idx())];
      out.write(reinterpret_cast<const char*>(&index), sizeof index);
    }
  }
  out.flush();
  return static_cast<bool>(out);
}

}  // namespace carbonmesh::detail
