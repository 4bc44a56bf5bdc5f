#include "carbonmesh/remesh/atomic_file.hpp"

#include <unistd.h>

#include <string>
#include <system_error>

#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh {

std::filesystem::path partial_path(const std::filesystem::path& target) {
  const std::string name = "." + target.stem().string() + ".partial-" + std::to_string(::getpid()) +
                           target.extension().string();
  return target.parent_path() / name;
}

void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write) {
  const auto tmp = partial_path(target);
  std::error_code ec;
  try {
    write(tmp);
  } catch (...) {
    std::filesystem::remove(tmp, ec);
    throw;
  }
  if (!std::filesystem::exists(tmp)) {
    throw InputError(target.string() + ": could not be written");
  }
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(target.string() + ": could not be written (" + ec.message() + ")");
  }
}

}  // namespace carbonmesh
