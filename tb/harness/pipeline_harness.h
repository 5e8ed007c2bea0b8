// SPDX-License-Identifier: Apache-2.0
// pipeline_harness.h: the file formats of tb/harness/pipeline_harness.cpp (the Verilator main that
// runs dm_pipeline, rtl/pipe/dm_pipeline.sv, on a whole frame of fragments).  tb/harness/dm_pipeline.py
// writes the input and reads the output with the same layout; keep the two in step (bump the
// versions on any change).
//
// All numbers are little-endian u32 words.
//
// Input file (tb/harness/dm_pipeline.py write_input):
//   header: 16 x u32 (64 bytes)
//     [0..1]   magic "PIPHIN01" (8 ASCII bytes)
//     [2]      version = 2
//     [3]      header bytes = 64
//     [4]      n_cfg_ports   = the number of entries of PIPH_CFG_PORTS below (17)
//     [5]      cfg_words     u32 words of the configuration section
//     [6]      n_tri_writes  triangle-table writes
//     [7]      n_frags       fragments
//     [8]      h_base        byte address of the height memory image (the pyramid), height port
//     [9]      h_bytes       its length
//     [10]     t_base        byte address of the texture memory image on the texture port
//     [11]     t_bytes       its length
//     [12]     frag_words    u32 words per fragment = 16
//     [13]     n_lvt_writes  texture level-table writes
//     [14..15] reserved (0)
//   configuration: for each port of PIPH_CFG_PORTS, in that order: one u32 holding the port's bit
//     width (checked against the table), then ceil(width / 32) u32 words of its value, least
//     significant word first (packed arrays as SystemVerilog packs them: element i at i * W);
//   triangle-table writes: n_tri_writes x 2 u32: tt_waddr_i, tt_wdata_i (pipeline_words.config);
//   level-table writes: n_lvt_writes x 2 u32: lvt_waddr_i, lvt_wdata_i (pipeline_words.config);
//   height image: h_bytes bytes (Pyramid.memory_image()), zero-padded to a multiple of 4;
//   texture image: t_bytes bytes (colour texture and normal map, each at the base address the
//     configuration's cfg_tex_base_i gives it, zeros between), zero-padded to a multiple of 4;
//   fragments: n_frags x 16 u32, in stream order: u0, v0, pl0 (f24 words), tri, TBN[0..8] (f24:
//     T (0..2), B (3..5), N (6..8)), view[0..2] (f24).  A fragment's pixel id is its index here.
//
// Output file (records in fragment order, whatever order the pixels left the unit in):
//   header: 4 x u32: magic "PIPHOUT1" (8 bytes), n_frags, record bytes = 16
//   record: 4 x u32: id (the fragment's index), rgb (R bits 7..0, G 15..8, B 23..16), flags (bit
//           0 hit, 1 invalid, 2 err), iterations
#pragma once

#include <cstdint>

// The configuration ports of dm_pipeline and their widths with the harness's parameters (the
// package constants of rtl/traverse/traverse_pkg.sv, rtl/pipe/pipe_pkg.sv, rtl/pipe/shade_pkg.sv).
// tb/harness/dm_pipeline.py CFG_PORTS is the same table.
#define PIPH_CFG_PORTS(X)                                                                         \
  X(cfg_method_i, 4)                                                                              \
  X(cfg_width_i, 16)                                                                              \
  X(cfg_height_i, 16)                                                                             \
  X(cfg_root_level_i, 4)                                                                          \
  X(cfg_bits16_i, 1)                                                                              \
  X(cfg_base_i, 32)                                                                               \
  X(cfg_root_code_i, 16)                                                                          \
  X(cfg_iter_cap_i, 16)                                                                           \
  X(cfg_depth_i, 24)                                                                              \
  X(cfg_mip_en_i, 1)                                                                              \
  X(cfg_levels_colour_i, 6)                                                                       \
  X(cfg_levels_normal_i, 6)                                                                       \
  X(cfg_shade_i, 192)                                                                             \
  X(cfg_miss_rgb_i, 24)                                                                           \
  X(cfg_tex_su_i, 48)                                                                             \
  X(cfg_tex_sv_i, 48)                                                                             \
  X(cfg_tex_base_i, 64)

namespace piph {

constexpr char kInMagic[8] = {'P', 'I', 'P', 'H', 'I', 'N', '0', '1'};
constexpr char kOutMagic[8] = {'P', 'I', 'P', 'H', 'O', 'U', 'T', '1'};
constexpr uint32_t kInVersion = 2;
#define PIPH_COUNT(name, bits) +1
constexpr uint32_t kCfgPorts = 0 PIPH_CFG_PORTS(PIPH_COUNT);
#undef PIPH_COUNT
constexpr uint32_t kFragWords = 16;

struct InHeader {
  char magic[8];
  uint32_t version;
  uint32_t header_bytes;
  uint32_t n_cfg_ports;
  uint32_t cfg_words;
  uint32_t n_tri_writes;
  uint32_t n_frags;
  uint32_t h_base;
  uint32_t h_bytes;
  uint32_t t_base;
  uint32_t t_bytes;
  uint32_t frag_words;
  uint32_t n_lvt_writes;
  uint32_t reserved[2];
};
static_assert(sizeof(InHeader) == 64, "input header is 64 bytes");

struct TableWrite {  // a write of the triangle table or of the texture level tables
  uint32_t addr, data;
};
static_assert(sizeof(TableWrite) == 8, "a table write is 8 bytes");

struct Fragment {
  uint32_t u0, v0, pl0, tri;
  uint32_t tbn[9];
  uint32_t view[3];
};
static_assert(sizeof(Fragment) == 4 * kFragWords, "a fragment is 16 words");

enum : uint32_t { kFlagHit = 1, kFlagInvalid = 2, kFlagErr = 4 };

struct OutHeader {
  char magic[8];
  uint32_t n_frags;
  uint32_t record_bytes;
};
static_assert(sizeof(OutHeader) == 16, "output header is 16 bytes");

struct OutRecord {
  uint32_t id, rgb, flags, iterations;
};
static_assert(sizeof(OutRecord) == 16, "an output record is 16 bytes");

}  // namespace piph
