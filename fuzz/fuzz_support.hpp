#pragma once
// Shared part of the libFuzzer harnesses: the input as a file in a private copy of configs/
// (so that relative robot and gait references of the shipped seeds resolve), and the rule
// that a reader may only fail with its documented exception — anything else (another
// exception, a sanitizer report, a crash, a hang) is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace gaitopt::fuzz {

// A directory of this process holding a copy of configs/robot and configs/gait.
inline const std::filesystem::path& workDir() {
  static const std::filesystem::path dir = [] {
    namespace fs = std::filesystem;
    const fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    const fs::path d = base / ("gaitopt_fuzz_" + std::to_string(::getpid()));
    fs::create_directories(d);
    for (const char* sub : {"robot", "gait"}) {
      fs::copy(fs::path(GAITOPT_SOURCE_DIR) / "configs" / sub, d / sub,
               fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    }
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(workDir(), ignored);
    });
    return d;
  }();
  return dir;
}

// Writes the input to <workDir>/<name> and returns that path.
inline std::string inputFile(const std::uint8_t* data, std::size_t size, const char* name) {
  const std::string path = (workDir() / name).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace gaitopt::fuzz
