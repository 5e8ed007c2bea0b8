// SPDX-License-Identifier: Apache-2.0
// harness_common.h: what the Verilator harnesses of tb/harness/ share besides the AXI memory
// (axi_mem.h): loud failure with an exit status, the random generator and biased coins of the
// stimulus, command-line number parsing, and setting Verilator ports of any width.
//
// Header-only; every harness defines its program name with `harness::set_name` before failing.
#pragma once

#include <cerrno>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>

namespace harness {

inline const char*& prog_name() {
  static const char* name = "harness";
  return name;
}
inline void set_name(const char* name) { prog_name() = name; }

// Print "<prog>: FAIL: <message>" on stderr and exit with `code`.
[[noreturn]] inline void fail(int code, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
inline void fail(int code, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  std::fprintf(stderr, "%s: FAIL: ", prog_name());
  std::vfprintf(stderr, fmt, ap);
  std::fprintf(stderr, "\n");
  va_end(ap);
  std::fflush(stdout);
  std::exit(code);
}

// xoshiro256** seeded through splitmix64.
struct Rng {
  uint64_t s[4];
  explicit Rng(uint64_t seed) {
    uint64_t z = seed;
    for (auto& w : s) {
      z += 0x9E3779B97F4A7C15ull;
      uint64_t x = z;
      x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
      x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
      w = x ^ (x >> 31);
    }
  }
  static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t next() {
    const uint64_t r = rotl(s[1] * 5, 7) * 9;
    const uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return r;
  }
  uint32_t range(uint32_t lo, uint32_t hi) {  // uniform in [lo, hi]
    if (hi <= lo) return lo;
    return lo + static_cast<uint32_t>(next() % (static_cast<uint64_t>(hi - lo) + 1));
  }
};

// A biased coin: true with probability p (no random draw at all when p == 0).
struct Coin {
  uint64_t thr = 0;
  bool on = false;
  void set(double p) {
    on = p > 0.0;
    thr = p >= 1.0 ? (1ull << 53) : static_cast<uint64_t>(p * 9007199254740992.0);
  }
  bool flip(Rng& r) const { return on && (r.next() >> 11) < thr; }
};

// Command-line numbers; a bad one is a usage error (exit status 1).
inline uint64_t parse_u64(const std::string& s, const char* what) {
  char* end = nullptr;
  errno = 0;
  unsigned long long v = std::strtoull(s.c_str(), &end, 0);
  if (s.empty() || errno != 0 || *end != '\0' || s[0] == '-')
    fail(1, "bad %s '%s' (a non-negative integer)", what, s.c_str());
  return v;
}

inline double parse_prob(const std::string& s, const char* what) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !(v >= 0.0 && v <= 1.0))
    fail(1, "bad %s '%s' (a probability in [0, 1])", what, s.c_str());
  return v;
}

// "L" or "MIN:MAX" -> [min, max] with 1 <= MIN <= MAX <= 1000000.
inline std::pair<uint32_t, uint32_t> parse_latency(const std::string& v, const char* what) {
  uint32_t lo, hi;
  const size_t c = v.find(':');
  if (c == std::string::npos) {
    lo = hi = static_cast<uint32_t>(parse_u64(v, what));
  } else {
    lo = static_cast<uint32_t>(parse_u64(v.substr(0, c), what));
    hi = static_cast<uint32_t>(parse_u64(v.substr(c + 1), what));
  }
  if (lo < 1 || hi < lo || hi > 1000000) fail(1, "%s: need 1 <= MIN <= MAX <= 1000000", what);
  return {lo, hi};
}

// "LO:HI" -> a non-empty byte range [LO, HI).
inline std::pair<uint64_t, uint64_t> parse_range(const std::string& v, const char* what) {
  const size_t c = v.find(':');
  if (c == std::string::npos) fail(1, "%s wants LO:HI", what);
  const uint64_t lo = parse_u64(v.substr(0, c), what), hi = parse_u64(v.substr(c + 1), what);
  if (hi <= lo) fail(1, "%s: empty range %s", what, v.c_str());
  return {lo, hi};
}

// Set a Verilator port of any width from little-endian bytes (nbytes of them; the rest of a wide
// port's words are cleared).  Integral ports (CData .. QData) take the low bytes.
template <typename T>
void set_bytes(T& port, const uint8_t* bytes, unsigned nbytes) {
  if constexpr (std::is_integral_v<T>) {
    T v = 0;
    std::memcpy(&v, bytes, nbytes < sizeof(T) ? nbytes : sizeof(T));  // little-endian host
    port = v;
  } else {  // VlWide<N>: 32-bit words, least significant first
    const unsigned words = sizeof(port) / 4;
    for (unsigned w = 0; w < words; ++w) {
      uint32_t x = 0;
      if (4 * w < nbytes) std::memcpy(&x, bytes + 4 * w, nbytes - 4 * w < 4 ? nbytes - 4 * w : 4);
      port[w] = x;
    }
  }
}

// The number of 32-bit words a port of T holds (1 or 2 for integral ports).
template <typename T>
constexpr unsigned port_words() {
  if constexpr (std::is_integral_v<T>)
    return sizeof(T) <= 4 ? 1 : 2;
  else
    return sizeof(T) / 4;
}

}  // namespace harness
