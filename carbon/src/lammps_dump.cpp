#include "carbonmesh/carbon/lammps_dump.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh {

DumpFrame read_last_dump_frame(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open", file.string()));
  DumpFrame last, frame;
  bool have = false;
  std::size_t count = 0;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("ITEM: TIMESTEP", 0) == 0) {
      if (!std::getline(in, line)) break;
      frame = DumpFrame{};
      frame.timestep = std::stol(line);
    } else if (line.rfind("ITEM: NUMBER OF ATOMS", 0) == 0) {
      if (!std::getline(in, line)) break;
      count = static_cast<std::size_t>(std::stol(line));
    } else if (line.rfind("ITEM: ATOMS", 0) == 0) {
      std::istringstream header(line.substr(11));
      std::vector<std::string> columns;
      for (std::string c; header >> c;) columns.push_back(c);
      auto column = [&](std::initializer_list<const char*> names) {
        for (const char* name : names) {
          const auto it = std::find(columns.begin(), columns.end(), name);
          if (it != columns.end()) return static_cast<std::size_t>(it - columns.begin());
        }
        throw InputError(fmt::format("{}: the dump has no column {}", file.string(), *names.begin()));
      };
      const std::size_t id = column({"id"}), type = column({"type"}), x = column({"x", "xu"}),
                        y = column({"y", "yu"}), z = column({"z", "zu"});
      std::vector<double> v(columns.size());
      bool complete = true;
      for (std::size_t i = 0; i < count; ++i) {
        if (!std::getline(in, line)) {
          complete = false;
          break;
        }
        std::istringstream ls(line);
        for (auto& value : v) ls >> value;
        if (!ls) {
          complete = false;
          break;
        }
        frame.ids.push_back(static_cast<int>(v[id]));
        frame.types.push_back(static_cast<int>(v[type]));
        frame.positions.emplace_back(v[x], v[y], v[z]);
      }
      if (!complete) break;
      std::vector<std::size_t> order(frame.ids.size());
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return frame.ids[a] < frame.ids[b]; });
      DumpFrame sorted;
      sorted.timestep = frame.timestep;
      for (std::size_t k : order) {
        sorted.ids.push_back(frame.ids[k]);
        sorted.types.push_back(frame.types[k]);
        sorted.positions.push_back(frame.positions[k]);
      }
      last = std::move(sorted);
      have = true;
    }
  }
  if (!have) throw InputError(fmt::format("{}: no complete dump frame", file.string()));
  return last;
}

}  // namespace carbonmesh
