#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <tuple>
#include <sstream>
#include <string>
#include <vector>

#include "binary_formats.hpp"
#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh::detail {
namespace {

// Corners at exactly the same position become one vertex.
class CornerMerger {
 public:
  explicit CornerMerger(PolygonSoup& soup) : soup_(soup) {}
  int add(const Vec3& p) {
    const auto key = std::make_tuple(p[0], p[1], p[2]);
    auto [it, inserted] = index_.emplace(key, static_cast<int>(soup_.points.size()));
    if (inserted) soup_.points.push_back(p);
    return it->second;
  }

 private:
  PolygonSoup& soup_;
  std::map<std::tuple<double, double, double>, int> index_;
};

}  // namespace

PolygonSoup read_stl(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(name + ": cannot be opened for reading");
  const auto size = std::filesystem::file_size(file);
  PolygonSoup soup;
  CornerMerger merger(soup);
  char header[84] = {};
  in.read(header, 84);
  std::uint32_t count = 0;
  std::memcpy(&count, header + 80, 4);
  const bool binary = in.gcount() == 84 && size == 84 + 50ull * count;
  if (binary) {
    for (std::uint32_t f = 0; f < count; ++f) {
      char record[50];
      if (!in.read(record, 50)) throw InputError(name + ": truncated binary STL (triangle " + std::to_string(f) + ")");
      std::vector<int> triangle;
      for (int c = 0; c < 3; ++c) {
        float xyz[3];
        std::memcpy(xyz, record + 12 + 12 * c, 12);
        triangle.push_back(merger.add(Vec3(xyz[0], xyz[1], xyz[2])));
      }
      soup.polygons.push_back(std::move(triangle));
    }
    return soup;
  }
  in.clear();
  in.seekg(0);
  std::string word;
  if (!(in >> word) || word != "solid")
    throw InputError(name + ": cannot be parsed as stl (neither binary nor ASCII 'solid')");
  std::vector<int> corners;
  std::string line;
  long line_number = 1;
  std::getline(in, line);
  while (std::getline(in, line)) {
    ++line_number;
    if (line.find('\0') != std::string::npos) throw InputError(name + ":" + std::to_string(line_number) + ": binary data in an ASCII STL");
    std::istringstream words(line);
    if (!(words >> word)) continue;
    if (word == "vertex") {
      std::string t[3];
      if (!(words >> t[0] >> t[1] >> t[2])) throw InputError(name + ":" + std::to_string(line_number) + ": a vertex needs three coordinates");
      double xyz[3];
      for (int c = 0; c < 3; ++c) {
        char* end = nullptr;
        xyz[c] = std::strtod(t[c].c_str(), &end);
        if (end == t[c].c_str() || *end != '\0')
          throw InputError(name + ":" + std::to_string(line_number) + ": '" + t[c] + "' is not a number");
      }
      corners.push_back(merger.add(Vec3(xyz[0], xyz[1], xyz[2])));
    } else if (word == "endloop") {
      if (corners.size() < 3) throw InputError(name + ":" + std::to_string(line_number) + ": a facet needs three vertices");
      soup.polygons.push_back(corners);
      corners.clear();
    }
  }
  if (!corners.empty()) throw InputError(name + ": truncated ASCII STL (a facet without endloop)");
  return soup;
}

}  // namespace carbonmesh::detail
