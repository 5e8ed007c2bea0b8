// SPDX-License-Identifier: Apache-2.0
// traverse_harness.h: the file formats of tb/harness/traverse_harness.cpp (the Verilator main that
// runs traverse_system on a whole ray batch).  tb/harness/traverse_system.py writes the input and reads the
// output with the same layout; keep the two in step (bump the versions on any change).
//
// All numbers are little-endian.
//
// Input file (tb/harness/traverse_system.py write_input):
//   header: 32 x u32 (128 bytes)
//     [0..1]   magic "TRVHIN01" (8 ASCII bytes)
//     [2]      version = 1
//     [3]      header bytes = 128
//     [4]      cfg_method        model.traverse.METHOD_CODES
//     [5]      cfg_width         W
//     [6]      cfg_height        H
//     [7]      cfg_root_level    n (N = 2^n)
//     [8]      cfg_bits16        1: unorm16 texels, 0: unorm8
//     [9]      cfg_base          byte address of the memory image (the pyramid) in AXI space
//     [10]     cfg_root_code     the root texel's code
//     [11]     cfg_iter_cap      model.traverse.iteration_cap(pyr)
//     [12]     n_rays
//     [13]     mem_bytes         length of the memory image
//     [14..29] level_off[0..15]  byte offset of level k from cfg_base (0 past the root): the
//              level-offset table, written through hlt_* after the reset
//     [30..31] reserved (0)
//   memory image: mem_bytes bytes (Pyramid.memory_image()), then zeros up to a multiple of 4
//   rays: n_rays x 4 u32: u0, v0, du, dv as f24 words (bits 23..0), ray by ray
//
// Output file (in input order, one record per ray):
//   header: 4 x u32: magic "TRVHOUT1" (8 bytes), n_rays, record bytes = 24
//   record: 6 x u32: id (the ray's index in the input), t, u, v (f24 words, meaningful when hit),
//           flags (bit 0 hit, 1 invalid, 2 capped, 3 err), iterations
#pragma once

#include <cstdint>

namespace trvh {

constexpr char kInMagic[8] = {'T', 'R', 'V', 'H', 'I', 'N', '0', '1'};
constexpr char kOutMagic[8] = {'T', 'R', 'V', 'H', 'O', 'U', 'T', '1'};
constexpr uint32_t kInVersion = 1;
constexpr uint32_t kMaxLevels = 16;

struct InHeader {
  char magic[8];
  uint32_t version;
  uint32_t header_bytes;
  uint32_t method;
  uint32_t width;
  uint32_t height;
  uint32_t root_level;
  uint32_t bits16;
  uint32_t base;
  uint32_t root_code;
  uint32_t iter_cap;
  uint32_t n_rays;
  uint32_t mem_bytes;
  uint32_t level_off[kMaxLevels];
  uint32_t reserved[2];
};
static_assert(sizeof(InHeader) == 128, "input header is 128 bytes");

struct Ray {
  uint32_t u0, v0, du, dv;
};
static_assert(sizeof(Ray) == 16, "a ray is 16 bytes");

enum : uint32_t { kFlagHit = 1, kFlagInvalid = 2, kFlagCapped = 4, kFlagErr = 8 };

struct OutHeader {
  char magic[8];
  uint32_t n_rays;
  uint32_t record_bytes;
};
static_assert(sizeof(OutHeader) == 16, "output header is 16 bytes");

struct OutRecord {
  uint32_t id, t, u, v, flags, iterations;
};
static_assert(sizeof(OutRecord) == 24, "an output record is 24 bytes");

}  // namespace trvh
