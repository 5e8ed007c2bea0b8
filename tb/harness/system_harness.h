// SPDX-License-Identifier: Apache-2.0
// system_harness.h: the file formats of tb/harness/system_harness.cpp (the Verilator main that plays
// CPU and memory for the system top rtl/top/pidm_top.sv on a whole frame).  tb/harness/pidm_system.py
// writes the input and reads the output with the same layout; keep the two in step (bump the
// versions on any change).
//
// All numbers are little-endian u32 words.
//
// Input file:
//   header: 16 x u32 (64 bytes)
//     [0..1]   magic "SYSHIN01"
//     [2]      version = 2
//     [3]      header bytes = 64
//     [4]      n_regions   memory regions that follow
//     [5]      n_writes    register writes (AXI4-Lite, in order; the last one starts the frame)
//     [6]      fb_base     byte address of the framebuffer (the write port's first buffer)
//     [7]      fb_bytes    its length
//     [8]      st_base     byte address of the status buffer (0 bytes: none)
//     [9]      st_bytes    its length
//     [10]     n_frags     fragments of the frame (pixels to be written)
//     [11]     n_pyr       the first n_pyr register writes are a pyramid build's (the last of them
//                          CTRL.pyr_start): the harness waits for its interrupt (pyr_done alone,
//                          ERROR 0) before the frame's writes; 0: no build
//     [12..15] reserved (0)
//   regions: n_regions x {port, base, bytes, then the bytes zero-padded to a multiple of 4};
//     port 0 = fragment reads (m_axi_f), 1 = heights (m_axi_h), 2 = textures (m_axi_t), 3 = the
//     framebuffer's initial contents, 4 = the status buffer's initial contents;
//   writes: n_writes x {byte address, value}.
//
// The write port (m_axi_w) writes the framebuffer, the status buffer and, during a pyramid
// build, the heights region (the height read port's memory: one memory, so a dirty rebuild and
// the frame read what the build wrote).
//
// Output file: header 8 x u32: magic "SYSHOUT2" (8 bytes), fb_bytes, st_bytes, h_bytes,
// pyr_cycles (clocks from CTRL.pyr_start to its interrupt; 0: no build), 2 reserved; then the
// framebuffer's, the status buffer's and the heights region's final bytes (each zero-padded to a
// multiple of 4).
#pragma once

#include <cstdint>

namespace sysh {

constexpr char kInMagic[8] = {'S', 'Y', 'S', 'H', 'I', 'N', '0', '1'};
constexpr char kOutMagic[8] = {'S', 'Y', 'S', 'H', 'O', 'U', 'T', '2'};
constexpr uint32_t kInVersion = 2;

enum : uint32_t { kPortF = 0, kPortH = 1, kPortT = 2, kPortFb = 3, kPortSt = 4 };

struct InHeader {
  char magic[8];
  uint32_t version;
  uint32_t header_bytes;
  uint32_t n_regions;
  uint32_t n_writes;
  uint32_t fb_base;
  uint32_t fb_bytes;
  uint32_t st_base;
  uint32_t st_bytes;
  uint32_t n_frags;
  uint32_t n_pyr;
  uint32_t reserved[4];
};
static_assert(sizeof(InHeader) == 64, "input header is 64 bytes");

struct RegionHeader {
  uint32_t port, base, bytes;
};

struct RegWrite {
  uint32_t addr, value;
};

}  // namespace sysh
