// common::Sha256 against the standard's vectors and against coreutils' sha256sum (an independent
// implementation) over files, alone and concatenated.
#include "common/sha256.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace adahrs::common {
namespace {

// The first field of `sha256sum`'s output for the shell words `args`.
std::string Sha256sum(const std::string& args) {
  std::string out;
  FILE* pipe = ::popen(("cat " + args + " | sha256sum").c_str(), "r");
  if (pipe == nullptr) return "popen failed";
  char buffer[128];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  ::pclose(pipe);
  return out.substr(0, out.find(' '));
}

// FIPS 180-2 appendix B.1 and B.2.
TEST(Sha256, MatchesTheStandardsVectors) {
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

// Files longer than one 64 KiB read block, hashed alone and one after the other, as sha256sum
// hashes them.
TEST(Sha256, FilesEqualSha256sum) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("adahrs_sha256_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::string a, b;
  for (int i = 0; i < 100000; ++i) a += static_cast<char>((i * 7919) & 0xFF);
  for (int i = 0; i < 70001; ++i) b += static_cast<char>((i * 31 + 5) & 0xFF);
  std::ofstream(dir / "a.bin", std::ios::binary) << a;
  std::ofstream(dir / "b.bin", std::ios::binary) << b;
  EXPECT_EQ(FileSha256(dir / "a.bin"), Sha256sum((dir / "a.bin").string()));
  Sha256 both;
  both.UpdateFile(dir / "a.bin");
  both.UpdateFile(dir / "b.bin");
  EXPECT_EQ(both.HexDigest(), Sha256sum((dir / "a.bin").string() + " " + (dir / "b.bin").string()));
  EXPECT_THAT([&] { FileSha256(dir / "missing.bin"); },
              ::testing::ThrowsMessage<std::runtime_error>(
                  ::testing::HasSubstr((dir / "missing.bin").string())));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adahrs::common
