#include "carbonmesh/remesh/atomic_file.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>

#include <string>
#include <system_error>

#include <fmt/format.h>

#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh {
namespace {

// Temporary files being written, readable from a signal handler (fixed slots, no allocation). This is the one
// piece of process-wide state in carbonmesh: signals are process-wide.
constexpr std::size_t kSlots = 64, kPathLength = 4096;
std::array<std::atomic<bool>, kSlots> slot_used{};
std::array<std::array<char, kPathLength>, kSlots> slot_path{};

int register_partial(const std::filesystem::path& tmp) {
  const std::string path = std::filesystem::absolute(tmp).string();
  if (path.size() >= kPathLength) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (slot_used[i].compare_exchange_strong(expected, true)) {
      std::memcpy(slot_path[i].data(), path.c_str(), path.size() + 1);
      return static_cast<int>(i);
    }
  }
  return -1;
}

void unregister_partial(int slot) {
  if (slot >= 0) slot_used[static_cast<std::size_t>(slot)].store(false);
}

extern "C" void remove_partials_and_reraise(int signal_number) {
  for (std::size_t i = 0; i < kSlots; ++i)
    if (slot_used[i].load()) ::unlink(slot_path[i].data());
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

}  // namespace

void remove_partial_files_on_interrupt() {
  struct sigaction action {};
  action.sa_handler = remove_partials_and_reraise;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

std::filesystem::path partial_path(const std::filesystem::path& target) {
  const std::string name =
      fmt::format(".{}.partial-{}{}", target.stem().string(), ::getpid(), target.extension().string());
  return target.parent_path() / name;
}

void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write) {
  const auto tmp = partial_path(target);
  std::error_code ec;
  const int slot = register_partial(tmp);
  try {
    write(tmp);
  } catch (...) {
    std::filesystem::remove(tmp, ec);
    unregister_partial(slot);
    throw;
  }
  if (!std::filesystem::exists(tmp)) {
    unregister_partial(slot);
    throw InputError(target.string() + ": could not be written");
  }
  std::filesystem::rename(tmp, target, ec);
  unregister_partial(slot);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(target.string() + ": could not be written (" + ec.message() + ")");
  }
}

}  // namespace carbonmesh
