// Turns a fuzzer's byte string into structured values (sizes, doubles with their special values,
// strings, byte blobs). Reads are little-endian and never fail: once the bytes run out every read
// returns zero / empty, so any input decodes to something. test/fuzz/make_seeds.py writes seeds in
// exactly this format; keep the two in step.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace costmap_layers_fuzz
{
class FuzzDecoder
{
public:
  FuzzDecoder(const uint8_t* data, std::size_t size) : p_(data), n_(size) {}

  std::size_t remaining() const { return n_ - pos_; }
  bool empty() const { return pos_ >= n_; }

  uint8_t u8() { return pos_ < n_ ? p_[pos_++] : 0; }
  uint16_t u16() { return static_cast<uint16_t>(uint64_t(u8()) | uint64_t(u8()) << 8); }
  uint32_t u32() { return static_cast<uint32_t>(uint64_t(u16()) | uint64_t(u16()) << 16); }
  uint64_t u64() { return uint64_t(u32()) | uint64_t(u32()) << 32; }
  int16_t i16() { return static_cast<int16_t>(u16()); }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  bool flag() { return (u8() & 1) != 0; }

  /// A value in [lo, hi] from 4 bytes.
  uint32_t range(uint32_t lo, uint32_t hi) { return hi <= lo ? lo : lo + u32() % (hi - lo + 1); }
  /// A small value in [lo, hi] from one byte.
  uint32_t small(uint32_t lo, uint32_t hi) { return hi <= lo ? lo : lo + u8() % (hi - lo + 1); }

  /// A size that is usually small (1 byte), sometimes anything (tag 255 + 4 bytes).
  uint32_t size()
  {
    const uint8_t b = u8();
    return b == 255 ? u32() : b;
  }

  /// A double: one tag byte, then the payload the tag asks for.
  ///   0 raw 8 bytes   1 zero    2 NaN     3 +inf   4 -inf   5 1e308   6 -1e308  7 1e-300
  ///   8 -0.0          9 DBL_MAX 10..12 int16 / 256 (2 bytes)   13..15 int32 / 1000 (4 bytes)
  /// Tags above 15 wrap (tag % 16).
  double real()
  {
    const uint8_t tag = u8() % 16;
    switch (tag)
    {
      case 0:
      {
        const uint64_t bits = u64();
        double v;
        std::memcpy(&v, &bits, sizeof v);
        return v;
      }
      case 1:
        return 0.0;
      case 2:
        return std::numeric_limits<double>::quiet_NaN();
      case 3:
        return std::numeric_limits<double>::infinity();
      case 4:
        return -std::numeric_limits<double>::infinity();
      case 5:
        return 1e308;
      case 6:
        return -1e308;
      case 7:
        return 1e-300;
      case 8:
        return -0.0;
      case 9:
        return std::numeric_limits<double>::max();
      case 10:
      case 11:
      case 12:
        return i16() / 256.0;
      default:
        return i32() / 1000.0;
    }
  }
  /// The same encoding, narrowed to float (1e308 becomes inf, 1e-300 becomes 0).
  float real32() { return static_cast<float>(real()); }

  /// Up to max_len bytes: one length byte (length % (max_len + 1)), then the bytes.
  std::string str(std::size_t max_len = 32)
  {
    const std::size_t len = u8() % (max_len + 1);
    std::string s;
    for (std::size_t k = 0; k < len && !empty(); ++k)
      s.push_back(static_cast<char>(u8()));
    return s;
  }

  /// n bytes (fewer when the input ends).
  std::vector<uint8_t> bytes(std::size_t n)
  {
    const std::size_t k = n < remaining() ? n : remaining();
    std::vector<uint8_t> out(p_ + pos_, p_ + pos_ + k);
    pos_ += k;
    return out;
  }
  /// Everything left.
  std::vector<uint8_t> rest() { return bytes(remaining()); }

private:
  const uint8_t* p_;
  std::size_t n_;
  std::size_t pos_ = 0;
};

/// What a grid's data vector holds relative to width x height.
///   0 exactly w*h values, 1 one value short, 2 one value too many, 3 empty, 4 an explicit length.
/// Values come from the input (cycled when it runs short), so masks hold -128..127 including the
/// invalid ones.
inline std::vector<int8_t> gridValues(FuzzDecoder& in, uint64_t cells, uint64_t cap)
{
  const uint8_t how = in.u8() % 5;
  uint64_t n = cells;
  if (how == 1) n = cells > 0 ? cells - 1 : 0;
  if (how == 2) n = cells + 1;
  if (how == 3) n = 0;
  if (how == 4) n = in.size();
  if (n > cap) n = cap;  // a length the decoder cannot afford is still a mismatch, just a cheaper one
  const std::vector<uint8_t> src = in.bytes(static_cast<std::size_t>(n < 4096 ? n : 4096));
  std::vector<int8_t> out(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = src.empty() ? 0 : static_cast<int8_t>(src[k % src.size()]);
  return out;
}
}  // namespace costmap_layers_fuzz
