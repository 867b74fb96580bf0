#pragma once
// The checksum of an HDF5 superblock of version 2 or 3 (HDF5 file format specification,
// "Superblock"), to repair file images taken by H5Fget_file_image. HDF5 1.10 clears the
// write-access flags of such a superblock in the image but keeps the checksum of the flags
// it had while open, so the image would not open again ("incorrect metadata checksum"). The
// checksum is Bob Jenkins' lookup3 hash of the superblock bytes with initial value 0, the
// function HDF5 uses for all its metadata checksums.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cosmpm::io::detail {

inline std::uint32_t lookup3(const unsigned char* k, std::size_t length, std::uint32_t initial) {
  auto rot = [](std::uint32_t x, int n) { return (x << n) | (x >> (32 - n)); };
  std::uint32_t a = 0xdeadbeefU + static_cast<std::uint32_t>(length) + initial;
  std::uint32_t b = a;
  std::uint32_t c = a;
  auto word = [&](std::size_t at, std::size_t count) {
    std::uint32_t w = 0;
    for (std::size_t i = 0; i < count; ++i) w += static_cast<std::uint32_t>(k[at + i]) << (8 * i);
    return w;
  };
  while (length > 12) {
    a += word(0, 4);
    b += word(4, 4);
    c += word(8, 4);
    a -= c, a ^= rot(c, 4), c += b;
    b -= a, b ^= rot(a, 6), a += c;
    c -= b, c ^= rot(b, 8), b += a;
    a -= c, a ^= rot(c, 16), c += b;
    b -= a, b ^= rot(a, 19), a += c;
    c -= b, c ^= rot(b, 4), b += a;
    length -= 12;
    k += 12;
  }
  if (length == 0) return c;
  a += word(0, length < 4 ? length : 4);
  if (length > 4) b += word(4, length < 8 ? length - 4 : 4);
  if (length > 8) c += word(8, length - 8);
  c ^= b, c -= rot(b, 14);
  a ^= c, a -= rot(c, 11);
  b ^= a, b -= rot(a, 25);
  c ^= b, c -= rot(b, 16);
  a ^= c, a -= rot(c, 4);
  b ^= a, b -= rot(a, 14);
  c ^= b, c -= rot(b, 24);
  return c;
}

// Recomputes the checksum of a version 2 or 3 superblock at the start of `image`; other
// versions carry no checksum and are left alone. Layout: signature (8 bytes), version,
// size of offsets (s), size of lengths, flags, then four addresses of s bytes and the
// checksum (4 bytes, little-endian).
inline void repair_superblock_checksum(std::vector<char>& image) {
  if (image.size() < 12) return;
  const auto* bytes = reinterpret_cast<const unsigned char*>(image.data());
  const unsigned version = bytes[8];
  const std::size_t offset_size = bytes[9];
  if (version != 2 && version != 3) return;
  const std::size_t covered = 12 + 4 * offset_size;
  if (image.size() < covered + 4) return;
  const std::uint32_t sum = lookup3(bytes, covered, 0);
  for (std::size_t i = 0; i < 4; ++i) {
    image[covered + i] = static_cast<char>((sum >> (8 * i)) & 0xffU);
  }
}

}  // namespace cosmpm::io::detail
