#include "carbonmesh/simulations/lammps_atoms.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>

#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh {
namespace {

constexpr long kMaxCount = 500'000'000;  // atoms/bonds beyond this are certainly garbage

std::vector<std::string_view> split(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
    std::size_t j = i;
    while (j < s.size() && !(s[j] == ' ' || s[j] == '\t' || s[j] == '\r')) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

std::string_view strip_comment(std::string_view s, std::string_view* comment = nullptr) {
  const auto hash = s.find('#');
  if (comment) *comment = hash == std::string_view::npos ? std::string_view{} : s.substr(hash + 1);
  return hash == std::string_view::npos ? s : s.substr(0, hash);
}

class Reader {
 public:
  explicit Reader(const std::filesystem::path& file) : name_(file.string()) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) throw InputError(name_ + ": no such file");
    if (std::filesystem::is_directory(file, ec)) throw InputError(name_ + ": is a folder, not a LAMMPS data file");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(name_ + ": cannot be opened for reading");
    std::ostringstream ss;
    ss << in.rdbuf();
    text_ = ss.str();
    if (text_.empty()) throw InputError(name_ + ": empty file");
    if (text_.find('\0') != std::string::npos) throw InputError(name_ + ": binary data, not a LAMMPS data file");
  }
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    auto end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    line = std::string_view(text_).substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_no_;
    return true;
  }
  // Peeks whether the next line exists without consuming it.
  std::size_t save() const { return pos_; }
  void restore(std::size_t pos, long line_no) {
    pos_ = pos;
    line_no_ = line_no;
  }
  long line_no() const { return line_no_; }
  std::size_t size() const { return text_.size(); }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}:{}: {}", name_, line_no_, what));
  }
  [[noreturn]] void fail_eof(const std::string& what) const {
    throw InputError(fmt::format("{}:{}: unexpected end of file: {}", name_, line_no_, what));
  }

 private:
  std::string name_, text_;
  std::size_t pos_ = 0;
  long line_no_ = 0;
};

template <class T>
std::optional<T> parse_number(std::string_view tok) {
  T value{};
  const char* first = tok.data();
  const char* last = tok.data() + tok.size();
  if (first != last && *first == '+') ++first;
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) return std::nullopt;
  }
  return value;
}

double number(const Reader& r, std::string_view tok, const char* what) {
  auto v = parse_number<double>(tok);
  if (!v) r.fail(fmt::format("{} '{}' is not a finite number", what, tok));
  return *v;
}
long integer(const Reader& r, std::string_view tok, const char* what) {
  auto v = parse_number<long>(tok);
  if (!v) r.fail(fmt::format("{} '{}' is not an integer", what, tok));
  return *v;
}

bool is_section_line(std::string_view line) {
  const auto toks = split(strip_comment(line));
  if (toks.empty()) return false;
  const char c = toks[0][0];
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

struct Style {
  std::string name;
  int columns = 0;  // without image flags
  int type_col = 1, x_col = 2;
};

std::optional<Style> style_named(std::string_view name) {
  if (name == "atomic") return Style{"atomic", 5, 1, 2};
  if (name == "full") return Style{"full", 7, 2, 4};
  if (name == "molecular" || name == "bond" || name == "angle") return Style{std::string(name), 6, 2, 3};
  if (name == "charge") return Style{"charge", 6, 1, 3};
  return std::nullopt;
}

}  // namespace

LammpsAtoms read_lammps_atoms(const std::filesystem::path& file) {
  Reader r(file);
  LammpsAtoms data;
  std::string_view line;
  if (!r.next(line)) r.fail_eof("no title line");
  data.title = std::string(line.substr(0, std::min<std::size_t>(line.size(), 200)));
  while (!data.title.empty() && (data.title.back() == '\r' || data.title.back() == ' ')) data.title.pop_back();

  long n_atoms = -1, n_bonds = 0;
  bool have_box[3] = {false, false, false};
  // Header: until the first section keyword.
  std::size_t pos = r.save();
  long line_no = r.line_no();
  while (r.next(line)) {
    const auto toks = split(strip_comment(line));
    if (toks.empty()) {
      pos = r.save();
      line_no = r.line_no();
      continue;
    }
    if (is_section_line(line)) {
      r.restore(pos, line_no);
      break;
    }
    auto has = [&](std::initializer_list<std::string_view> words) {
      if (toks.size() < words.size() + 1) return false;
      std::size_t k = toks.size() - words.size();
      for (auto w : words)
        if (toks[k++] != w) return false;
      return true;
    };
    auto count = [&](const char* what) {
      const long v = integer(r, toks[0], what);
      if (v < 0 || v > kMaxCount) r.fail(fmt::format("{} {} out of range", what, v));
      return v;
    };
    if (has({"atoms"}) && toks.size() == 2) {
      n_atoms = count("atom count");
    } else if (has({"bonds"}) && toks.size() == 2) {
      n_bonds = count("bond count");
    } else if (has({"atom", "types"}) && toks.size() == 3) {
      const long t = count("atom type count");
      if (t < 1 || t > 100000) r.fail(fmt::format("atom type count {} out of range", t));
      data.atom_types = static_cast<int>(t);
    } else if (toks.size() == 4 && (has({"xlo", "xhi"}) || has({"ylo", "yhi"}) || has({"zlo", "zhi"}))) {
      const int k = toks[2][0] - 'x';
      data.box_lo[k] = number(r, toks[0], "box bound");
      data.box_hi[k] = number(r, toks[1], "box bound");
      if (!(data.box_lo[k] < data.box_hi[k])) r.fail(fmt::format("empty box: {} >= {}", toks[0], toks[1]));
      have_box[k] = true;
    } else if (toks.size() == 6 && has({"xy", "xz", "yz"})) {
      for (int k = 0; k < 3; ++k) data.tilt[k] = number(r, toks[k], "tilt factor");
    } else if (toks.size() >= 2 && (toks.back() == "types" || toks.back() == "angles" || toks.back() == "dihedrals" ||
                                    toks.back() == "impropers" || toks.back() == "extra" || toks.back() == "per" ||
                                    toks[toks.size() - 2] == "extra" || toks[toks.size() - 2] == "per")) {
      integer(r, toks[0], "count");  // other counts: checked, not used
    } else if (toks.size() >= 2 && (toks.back() == "ellipsoids" || toks.back() == "lines" ||
                                    toks.back() == "triangles" || toks.back() == "bodies")) {
      integer(r, toks[0], "count");
    } else {
      r.fail(fmt::format("unrecognised header line '{}'", std::string(strip_comment(line)).substr(0, 80)));
    }
    pos = r.save();
    line_no = r.line_no();
  }
  if (n_atoms < 0) r.fail("header has no 'N atoms' line");
  if (n_atoms == 0) r.fail("the file declares 0 atoms");
  if (data.atom_types == 0) r.fail("header has no 'N atom types' line");
  for (int k = 0; k < 3; ++k)
    if (!have_box[k]) r.fail(fmt::format("header has no '{}lo {}hi' box line", char('x' + k), char('x' + k)));
  data.masses.assign(data.atom_types, 0.0);

  bool have_atoms = false;
  std::unordered_map<long, int> index_of;
  std::vector<std::array<long, 2>> bond_ids;
  auto skip_blank = [&](const char* section) {
    std::size_t p = r.save();
    long ln = r.line_no();
    while (r.next(line)) {
      if (!split(strip_comment(line)).empty()) {
        r.restore(p, ln);
        return;
      }
      p = r.save();
      ln = r.line_no();
    }
    r.fail_eof(fmt::format("the {} section is empty", section));
  };
  while (r.next(line)) {
    std::string_view comment;
    const auto toks = split(strip_comment(line, &comment));
    if (toks.empty()) continue;
    if (!is_section_line(line)) r.fail(fmt::format("expected a section name, found '{}'", toks[0]));
    const std::string section(toks[0]);
    if (section == "Masses") {
      skip_blank("Masses");
      for (int k = 0; k < data.atom_types; ++k) {
        if (!r.next(line)) r.fail_eof(fmt::format("Masses has {} of {} lines", k, data.atom_types));
        const auto t = split(strip_comment(line));
        if (t.size() < 2) r.fail("a Masses line needs 'type mass'");
        const long type = integer(r, t[0], "atom type");
        if (type < 1 || type > data.atom_types)
          r.fail(fmt::format("atom type {} out of range 1..{}", type, data.atom_types));
        const double m = number(r, t[1], "mass");
        if (!(m > 0)) r.fail(fmt::format("mass {} must be positive", m));
        data.masses[type - 1] = m;
      }
    } else if (section == "Atoms") {
      if (have_atoms) r.fail("second Atoms section");
      have_atoms = true;
      std::optional<Style> style;
      const auto hint = split(comment);
      if (!hint.empty()) {
        style = style_named(hint[0]);
        if (!style) r.fail(fmt::format("atom style '{}' is not supported (atomic, full, molecular, bond, charge)", hint[0]));
      }
      skip_blank("Atoms");
      // An atom line has at least 10 characters: never reserve more than the file can hold.
      const std::size_t reserve = std::min(static_cast<std::size_t>(n_atoms), r.size() / 10 + 1);
      data.ids.reserve(reserve);
      data.types.reserve(reserve);
      data.positions.reserve(reserve);
      index_of.reserve(reserve);
      for (long k = 0; k < n_atoms; ++k) {
        if (!r.next(line)) r.fail_eof(fmt::format("Atoms has {} of {} lines", k, n_atoms));
        const auto t = split(strip_comment(line));
        if (!style) {  // infer once from the first line
          if (t.size() == 5 || t.size() == 8) style = style_named("atomic");
          else if (t.size() == 7 || t.size() == 10) style = style_named("full");
          else r.fail(fmt::format("cannot infer the atom style from {} columns; add '# atomic' or '# full' after Atoms", t.size()));
          data.atom_style = style->name;
        }
        if (!(t.size() == static_cast<std::size_t>(style->columns) || t.size() == static_cast<std::size_t>(style->columns + 3)))
          r.fail(fmt::format("an Atoms line of style {} needs {} or {} columns, found {}", style->name, style->columns,
                             style->columns + 3, t.size()));
        const long id = integer(r, t[0], "atom id");
        if (id < 1) r.fail(fmt::format("atom id {} must be positive", id));
        const long type = integer(r, t[style->type_col], "atom type");
        if (type < 1 || type > data.atom_types)
          r.fail(fmt::format("atom type {} out of range 1..{}", type, data.atom_types));
        Vec3 p;
        for (int c = 0; c < 3; ++c) p[c] = number(r, t[style->x_col + c], "coordinate");
        for (std::size_t c = style->columns; c < t.size(); ++c) integer(r, t[c], "image flag");
        if (!index_of.emplace(id, static_cast<int>(data.ids.size())).second)
          r.fail(fmt::format("duplicate atom id {}", id));
        data.ids.push_back(id);
        data.types.push_back(static_cast<int>(type));
        data.positions.push_back(p);
      }
      if (data.atom_style.empty()) data.atom_style = style->name;
    } else if (section == "Bonds") {
      skip_blank("Bonds");
      for (long k = 0; k < n_bonds; ++k) {
        if (!r.next(line)) r.fail_eof(fmt::format("Bonds has {} of {} lines", k, n_bonds));
        const auto t = split(strip_comment(line));
        if (t.size() != 4) r.fail(fmt::format("a Bonds line needs 'id type atom1 atom2', found {} columns", t.size()));
        integer(r, t[0], "bond id");
        integer(r, t[1], "bond type");
        bond_ids.push_back({integer(r, t[2], "atom id"), integer(r, t[3], "atom id")});
      }
    } else {
      // Any other section (Velocities, Angles, Pair Coeffs, ...): skip its lines up to the next section name.
      skip_blank(section.c_str());
      std::size_t p = r.save();
      long ln = r.line_no();
      while (r.next(line)) {
        if (is_section_line(line)) break;
        p = r.save();
        ln = r.line_no();
      }
      r.restore(p, ln);
    }
  }
  if (!have_atoms) r.fail("no Atoms section");
  for (const auto& b : bond_ids) {
    auto a = index_of.find(b[0]), c = index_of.find(b[1]);
    if (a == index_of.end() || c == index_of.end())
      throw InputError(fmt::format("{}: a bond names atom id {} that is not in Atoms", file.string(),
                                   a == index_of.end() ? b[0] : b[1]));
    data.bonds.push_back({std::min(a->second, c->second), std::max(a->second, c->second)});
  }
  return data;
}

}  // namespace carbonmesh
