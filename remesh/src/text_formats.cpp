#include "text_formats.hpp"

#include "binary_formats.hpp"  // printable

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/os.h>

#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh::detail {
namespace {

// Lines of a text file with their numbers; '#' starts a comment.
class LineReader {
 public:
  explicit LineReader(const std::filesystem::path& file) : file_(file), in_(file, std::ios::binary) {
    if (!in_) throw InputError(file.string() + ": cannot be opened for reading");
  }
  // Next line with content (comments and blank lines skipped); false at the end.
  bool next(std::vector<std::string>& tokens) {
    std::string line;
    while (std::getline(in_, line)) {
      ++number_;
      if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
      if (line.find('\0') != std::string::npos) fail("binary data in a text file");
      tokens.clear();
      std::istringstream words(line);
      for (std::string word; words >> word;) tokens.push_back(word);
      if (!tokens.empty()) return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(file_.string() + ":" + std::to_string(number_) + ": " + problem);
  }
  double number(const std::string& token) const {
    const char* begin = token.c_str();
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(begin, &end);
    if (end == begin || *end != '\0') fail(fmt::format("'{}' is not a number", printable(token)));
    return value;  // NaN and Inf are reported by the mesh validation, with the vertex index
  }
  long integer(const std::string& token) const {
    const char* begin = token.c_str();
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(begin, &end, 10);
    if (end == begin || *end != '\0' || errno == ERANGE) fail(fmt::format("'{}' is not an integer", printable(token)));
    return value;
  }
  int line() const { return number_; }

 private:
  std::filesystem::path file_;
  std::ifstream in_;
  int number_ = 0;
};

constexpr long kMaxElements = 200'000'000;

}  // namespace

PolygonSoup read_off(const std::filesystem::path& file) {
  LineReader reader(file);
  std::vector<std::string> t;
  if (!reader.next(t)) reader.fail("no OFF header");
  std::size_t pos = 0;
  const std::string& keyword = t[0];
  if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0)
    reader.fail("not an OFF file (the first word is '" + printable(keyword) + "', expected OFF)");
  if (keyword.find("4") != std::string::npos || keyword.find("n") == 0)
    reader.fail("unsupported OFF variant '" + printable(keyword) + "' (only 3D OFF is read)");
  pos = 1;
  if (pos >= t.size()) {
    if (!reader.next(t)) reader.fail("truncated: no vertex and face counts");
    pos = 0;
  }
  if (t.size() - pos < 2) reader.fail("expected the vertex and face counts");
  const long nv = reader.integer(t[pos]), nf = reader.integer(t[pos + 1]);
  if (nv < 0 || nf < 0 || nv > kMaxElements || nf > kMaxElements)
    reader.fail("implausible counts " + std::to_string(nv) + " vertices, " + std::to_string(nf) + " faces");
  PolygonSoup soup;
  // A vertex or face line takes at least 6 bytes: never reserve more than the file could hold.
  const auto plausible = static_cast<long>(std::filesystem::file_size(file) / 6 + 1);
  soup.points.reserve(static_cast<std::size_t>(std::min(nv, plausible)));
  soup.polygons.reserve(static_cast<std::size_t>(std::min(nf, plausible)));
  for (long i = 0; i < nv; ++i) {
    if (!reader.next(t))
      reader.fail("truncated: expected " + std::to_string(nv) + " vertices, found " + std::to_string(i));
    if (t.size() < 3) reader.fail("a vertex needs three coordinates");
    soup.points.emplace_back(reader.number(t[0]), reader.number(t[1]), reader.number(t[2]));
  }
  for (long f = 0; f < nf; ++f) {
    if (!reader.next(t))
      reader.fail("truncated: expected " + std::to_string(nf) + " faces, found " + std::to_string(f));
    const long n = reader.integer(t[0]);
    if (n < 0 || static_cast<std::size_t>(n) + 1 > t.size())
      reader.fail("face " + std::to_string(f) + " announces " + std::to_string(n) + " corners but lists " +
                  std::to_string(t.size() - 1));
    std::vector<int> polygon;
    polygon.reserve(static_cast<std::size_t>(n));
    for (long k = 1; k <= n; ++k) {
      const long index = reader.integer(t[static_cast<std::size_t>(k)]);
      if (index < 0 || index >= nv)
        reader.fail("face " + std::to_string(f) + " refers to vertex " + std::to_string(index) +
                    ", out of range (the file has " + std::to_string(nv) + " vertices)");
      polygon.push_back(static_cast<int>(index));
    }
    soup.polygons.push_back(std::move(polygon));
  }
  return soup;
}

PolygonSoup read_obj(const std::filesystem::path& file) {
  LineReader reader(file);
  PolygonSoup soup;
  std::vector<std::string> t;
  while (reader.next(t)) {
    if (t[0] == "v") {
      if (t.size() < 4) reader.fail("a vertex needs three coordinates");
      soup.points.emplace_back(reader.number(t[1]), reader.number(t[2]), reader.number(t[3]));
    } else if (t[0] == "f") {
      if (t.size() < 4) reader.fail("a face needs at least three corners");
      std::vector<int> polygon;
      for (std::size_t k = 1; k < t.size(); ++k) {
        const std::string index_text = t[k].substr(0, t[k].find('/'));
        long index = reader.integer(index_text);
        const long n = static_cast<long>(soup.points.size());
        if (index < 0) index = n + index + 1;  // relative index
        if (index < 1 || index > n)
          reader.fail("face refers to vertex " + index_text + ", out of range (" + std::to_string(n) +
                      " vertices so far)");
        polygon.push_back(static_cast<int>(index - 1));
      }
      soup.polygons.push_back(std::move(polygon));
    }
    // Other statements (vn, vt, g, o, s, usemtl, mtllib, l) carry nothing carbonmesh uses.
  }
  return soup;
}

namespace {

// Vertex indices in iteration order (the mesh may hold deleted elements).
std::vector<int> vertex_numbers(const TriMesh& mesh) {
  std::vector<int> number(mesh.n_vertices(), -1);
  int next = 0;
  for (auto v : mesh.vertices()) number[static_cast<std::size_t>(v.idx())] = next++;
  return number;
}

template <typename WriteVertex, typename WriteFace>
bool write_text(const TriMesh& mesh, const std::filesystem::path& file, const std::string& header,
                WriteVertex write_vertex, WriteFace write_face) {
  std::ofstream out(file, std::ios::binary);
  if (!out) return false;
  out << header;
  for (auto v : mesh.vertices()) out << write_vertex(mesh.point(v));
  const auto number = vertex_numbers(mesh);
  for (auto f : mesh.faces()) {
    int c[3], k = 0;
    for (auto v : mesh.fv_range(f)) c[k++] = number[static_cast<std::size_t>(v.idx())];
    out << write_face(c);
  }
  out.flush();
  return static_cast<bool>(out);
}

std::size_t live_vertices(const TriMesh& mesh) {
  std::size_t n = 0;
  for ([[maybe_unused]] auto v : mesh.vertices()) ++n;
  return n;
}

std::size_t live_faces(const TriMesh& mesh) {
  std::size_t n = 0;
  for ([[maybe_unused]] auto f : mesh.faces()) ++n;
  return n;
}

}  // namespace

bool write_off(const TriMesh& mesh, const std::filesystem::path& file) {
  return write_text(
      mesh, file, fmt::format("OFF\n{} {} 0\n", live_vertices(mesh), live_faces(mesh)),
      [](const Vec3& p) { return fmt::format("{:.17g} {:.17g} {:.17g}\n", p[0], p[1], p[2]); },
      [](const int* c) { return fmt::format("3 {} {} {}\n", c[0], c[1], c[2]); });
}

bool write_obj(const TriMesh& mesh, const std::filesystem::path& file) {
  return write_text(
      mesh, file, fmt::format("# carbonmesh: {} vertices, {} faces\n", live_vertices(mesh), live_faces(mesh)),
      [](const Vec3& p) { return fmt::format("v {:.17g} {:.17g} {:.17g}\n", p[0], p[1], p[2]); },
      [](const int* c) { return fmt::format("f {} {} {}\n", c[0] + 1, c[1] + 1, c[2] + 1); });
}

}  // namespace carbonmesh::detail
