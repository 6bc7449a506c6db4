// Formats one CSV row into a caller's buffer with std::to_chars: the same text as printf's "%u",
// "%d" and "%.Nf" (to_chars rounds the exact binary value as glibc's printf does, ties to even),
// and the shortest text that reads back to the same double, without a locale or a call per cell.
#pragma once

#include <charconv>
#include <cstdint>
#include <string_view>
#include <vector>

namespace adahrs::hil {

class RowText {
 public:
  /// Starts a row in `buffer`, grown to hold `text_bytes` of free-form text (the unit serial)
  /// and any numbers a row has.
  RowText(std::vector<char>& buffer, size_t text_bytes) {
    const size_t needed = text_bytes + kRowNumberBytes;
    if (buffer.size() < needed) buffer.resize(needed);
    begin_ = buffer.data();
    end_ = begin_ + buffer.size();
    at_ = begin_;
  }

  void Comma() { *at_++ = ','; }
  void Char(char c) { *at_++ = c; }
  void Text(std::string_view text) {
    for (char c : text) *at_++ = c;
  }
  template <typename Int>
  void Integer(Int value) {
    at_ = std::to_chars(at_, end_, value).ptr;
  }
  /// As printf's "%.<digits>f".
  void Fixed(double value, int digits) {
    at_ = std::to_chars(at_, end_, value, std::chars_format::fixed, digits).ptr;
  }
  /// The shortest text that reads back to `value`.
  void Shortest(double value) { at_ = std::to_chars(at_, end_, value).ptr; }

  const char* data() const { return begin_; }
  size_t size() const { return static_cast<size_t>(at_ - begin_); }

 private:
  // Room for any row's numbers: a fixed-point double of 1e308 takes 315 characters, the
  // shortest double 24, an integer 11; an IMU row has 3, 9 and 24 of them.
  static constexpr size_t kRowNumberBytes = 4096;
  char* begin_ = nullptr;
  char* end_ = nullptr;
  char* at_ = nullptr;
};

}  // namespace adahrs::hil
