// GzipReader against files compressed by zlib, an independent writer: members larger than the
// reader's text buffer, a file larger than its input window, empty members, a cut last member.
#include "hil/recording/gzip_reader.h"

#include <unistd.h>
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace adahrs::hil {
namespace {

// One gzip member of `text` made by zlib.
std::string ZlibMember(const std::string& text) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&z, text.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

// CSV-like rows of pseudo-random digits (compressing to about half).
std::string Rows(size_t bytes, uint64_t seed) {
  std::string text;
  uint64_t x = seed;
  while (text.size() < bytes) {
    for (int cell = 0; cell < 12; ++cell) {
      x = x * 6364136223846793005u + 1442695040888963407u;
      text += std::to_string(x >> 44);
      text += cell == 11 ? '\n' : ',';
    }
  }
  return text;
}

std::string ReadAll(GzipReader& reader) {
  std::string text;
  std::vector<char> chunk(65536);
  while (const size_t n = reader.Read(chunk.data(), chunk.size())) text.append(chunk.data(), n);
  return text;
}

class GzipReaderTest : public testing::Test {
 protected:
  std::filesystem::path path_ = std::filesystem::temp_directory_path() /
                                ("adahrs-gzip-reader-" + std::to_string(::getpid()) + ".csv.gz");
  void TearDown() override { std::filesystem::remove(path_); }
  void Write(const std::string& bytes) { std::ofstream(path_, std::ios::binary) << bytes; }
};

TEST_F(GzipReaderTest, MembersLargerThanTheBufferAndAFileLargerThanTheWindowReadWhole) {
  // 3 MiB in one member (the reader's text buffer starts at 1 MiB), then 512 KiB members to
  // about 14 MiB of text (over 4 MiB compressed: the reader's first input window), with an
  // empty member among them.
  std::string text;
  std::string file;
  const std::string big = Rows(3u << 20, 1);
  text += big;
  file += ZlibMember(big);
  file += ZlibMember("");
  for (uint64_t m = 0; m < 22; ++m) {
    const std::string part = Rows(512u << 10, 100 + m);
    text += part;
    file += ZlibMember(part);
  }
  ASSERT_GT(file.size(), size_t{4} << 20);
  Write(file);
  GzipReader reader(path_);
  EXPECT_EQ(ReadAll(reader), text);
  EXPECT_FALSE(reader.truncated());
  EXPECT_EQ(reader.complete_bytes(), file.size());
}

TEST_F(GzipReaderTest, AFileCutInsideItsLastMemberReadsTheCompleteMembersAndThenTheCut) {
  std::string text;
  std::string file;
  for (uint64_t m = 0; m < 12; ++m) {
    const std::string part = Rows(512u << 10, 7 + m);
    text += part;
    file += ZlibMember(part);
  }
  const size_t complete = file.size();
  const std::string last = Rows(512u << 10, 99);
  const std::string last_member = ZlibMember(last);
  file += last_member.substr(0, last_member.size() / 2);
  Write(file);
  GzipReader reader(path_);
  const std::string read = ReadAll(reader);
  EXPECT_TRUE(reader.truncated());
  EXPECT_EQ(reader.complete_bytes(), complete);
  ASSERT_GT(read.size(), text.size());  // the cut member's text up to the cut follows
  EXPECT_EQ(read.substr(0, text.size()), text);
  EXPECT_EQ(read.substr(text.size()), last.substr(0, read.size() - text.size()));
}

TEST_F(GzipReaderTest, BytesAfterACompleteMemberThatAreNotAMemberAreRefused) {
  const std::string part = Rows(64u << 10, 3);
  Write(ZlibMember(part) + std::string("not gzip at all, but long enough to look like data"));
  GzipReader reader(path_);
  EXPECT_THROW(ReadAll(reader), std::runtime_error);
}

}  // namespace
}  // namespace adahrs::hil
