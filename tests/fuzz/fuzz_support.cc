#include "tests/fuzz/fuzz_support.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace adahrs::fuzz {

const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::filesystem::path base = tmp != nullptr && *tmp != '\0' ? tmp : "/tmp";
    auto path = base / ("adahrs-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  return dir;
}

std::filesystem::path WriteScratchFile(std::string_view name, const uint8_t* data, size_t size) {
  auto path = ScratchDir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::logic_error("fuzz: cannot write " + path.string());
  return path;
}

void CopyToScratch(const std::filesystem::path& source, std::string_view name) {
  std::filesystem::copy_file(
      source, ScratchDir() / name, std::filesystem::copy_options::overwrite_existing);
}

}  // namespace adahrs::fuzz
