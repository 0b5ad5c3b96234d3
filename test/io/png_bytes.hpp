// Hand-built PNG bytes for the file tests: crafted headers a real encoder would never write.
#pragma once

#include <cstdint>
#include <string>

/// The CRC-32 a PNG chunk carries (over its type and data).
inline uint32_t pngCrc32(const std::string& bytes)
{
  uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes)
  {
    c ^= b;
    for (int k = 0; k < 8; ++k)
      c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

/// v as 4 big-endian bytes.
inline std::string be32(uint32_t v)
{
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

/// One chunk: length, type, data, CRC.
inline std::string pngChunk(const std::string& type, const std::string& data)
{
  return be32(static_cast<uint32_t>(data.size())) + type + data + be32(pngCrc32(type + data));
}
