#pragma once
// Atomic outputs: everything is written to a temporary name in the target folder, then renamed into place.
#include <filesystem>
#include <functional>

namespace carbonmesh {

// The temporary name used for `target`: same folder and extension, a hidden ".partial-<pid>" stem.
std::filesystem::path partial_path(const std::filesystem::path& target);

// Calls write(tmp) and renames tmp onto target. If write throws or leaves no file, tmp is removed and the
// target is untouched.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

// Installs SIGINT/SIGTERM handlers that remove the temporary files being written and then end the process
// with the signal (non-zero exit). The CLI calls it once at start.
void remove_partial_files_on_interrupt();

}  // namespace carbonmesh
