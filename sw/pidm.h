// SPDX-License-Identifier: Apache-2.0
// pidm: a small host driver for the pidm_top core (pyramidal inverse displacement mapping) over
// its AXI4-Lite registers.  Register offsets and fields come from the generated header
// sw/pidm_regs.h (rtl/top/pidm_regs.rdl; docs/registers.md); the memory formats (fragment
// record, framebuffer pixel, status word) are in docs/system.md.
//
// A frame:
//   struct pidm_dev dev;
//   if (pidm_init(&dev, (volatile void *)0x43C00000) != PIDM_OK) ...   // checks ID and VERSION
//   pidm_load_config(&dev, writes, n_writes);     // the list scripts/pack_frame.py writes
//   pidm_start(&dev, &frame);                     // the frame descriptor, then CTRL.start
//   rc = pidm_poll_done(&dev, 100000000);         // or: interrupts (pidm_irq_handler)
//   pidm_read_stats(&dev, &stats);
//
// A pyramid build (the hardware builder, PYR registers; level 0 already in memory):
//   struct pidm_pyr p = {.src_base = b, .pyr_base = b, .width = w, .height = h};
//   pidm_pyr_full(&p);                            // dirty rectangle = the whole map, offsets
//   pidm_pyr_start(&dev, &p);                     // PYR registers, then CTRL.pyr_start
//   rc = pidm_pyr_poll_done(&dev, 1000000);       // or: the PIDM_IRQ_PYR_DONE interrupt
// (pidm_pyr_build does the three.)  The build's end invalidates the core's height cache; a
// frame started after it reads the new pyramid.
//
// Every register access goes through pidm_rd / pidm_wr: a volatile 32-bit load or store at
// base + offset, unless pidm_set_mmio installed other accessors (a bus bridge, a simulator, the
// unit test's register model).  The driver keeps no hidden state besides the last interrupt
// causes seen by pidm_irq_handler.  The core ignores AXI4-Lite write strobes (every write writes
// the whole 32-bit register: only 32-bit stores) and its per-level tables (LEVEL_OFF,
// LEVEL_SIZE) are write-only (they read 0): the driver never reads them back.
#ifndef PIDM_H
#define PIDM_H

#include <stddef.h>
#include <stdint.h>

#include "pidm_regs.h"

#ifdef __cplusplus
extern "C" {
#endif

// ---- return codes ---------------------------------------------------------------------------
#define PIDM_OK           0
#define PIDM_ERR_ID      -1  // ID or VERSION major does not match: not a pidm_top
#define PIDM_ERR_BUSY    -2  // a frame or a pyramid build is running
#define PIDM_ERR_HW      -3  // the frame ended with ERROR flags set (pidm_error_flags)
#define PIDM_ERR_TIMEOUT -4  // the poll / wait budget ran out
#define PIDM_ERR_ARG     -5  // a bad argument (NULL, an address outside the configuration)

#define PIDM_ID_VALUE      0x5049444Du  // "PIDM" (ID reset value)
#define PIDM_VERSION_MAJOR 1u

// Interrupt causes (INTR_STATE / INTR_ENABLE / INTR_TEST bits).
#define PIDM_IRQ_FRAME_DONE PIDM_REGS__INTR_STATE__FRAME_DONE_bm
#define PIDM_IRQ_AXI_ERROR  PIDM_REGS__INTR_STATE__AXI_ERROR_bm
#define PIDM_IRQ_PYR_DONE   PIDM_REGS__INTR_STATE__PYR_DONE_bm
#define PIDM_IRQ_FRAME      (PIDM_IRQ_FRAME_DONE | PIDM_IRQ_AXI_ERROR)  // a frame's causes
#define PIDM_IRQ_ALL        (PIDM_IRQ_FRAME_DONE | PIDM_IRQ_AXI_ERROR | PIDM_IRQ_PYR_DONE)

// Pyramid levels the PYR block describes (PYR.LEVEL_OFF entries).
#define PIDM_PYR_LEVELS 16u

// Configuration space a register write list may touch: TT_WRITE and HEIGHT .. the end of TEX
// (the PYR block is written by pidm_pyr_start only).
#define PIDM_OFF(reg) ((uint32_t)offsetof(pidm_regs_t, reg))

struct pidm_dev;
typedef uint32_t (*pidm_rd_fn)(struct pidm_dev *dev, uint32_t off);
typedef void (*pidm_wr_fn)(struct pidm_dev *dev, uint32_t off, uint32_t value);

struct pidm_dev {
    volatile uint32_t *base;  // the register block's first word
    pidm_rd_fn rd;            // NULL: volatile load at base
    pidm_wr_fn wr;            // NULL: volatile store at base
    void *ctx;                // for the accessors
    uint32_t hwcfg;           // HWCFG, read by pidm_init
    volatile uint32_t irq_seen;  // INTR_STATE bits pidm_irq_handler has taken
};

// One register write: a byte offset in the map and the 32-bit value.
struct pidm_reg_write {
    uint32_t off;
    uint32_t value;
};

// The frame descriptor (FRAME registers).
struct pidm_frame {
    uint64_t frag_base;    // fragment records, FRAG_BYTES (64) aligned
    uint32_t frag_count;   // at least 1
    uint64_t fb_base;      // RGBA8 framebuffer, 4-byte aligned
    uint32_t fb_pitch;     // bytes per row, a multiple of 4
    uint32_t xbits;        // pixel id = {y, x}: x in the low xbits bits
    uint64_t status_base;  // per-pixel status words (same layout as the framebuffer)
    int status_en;         // write status words
};

// A pyramid build (PYR registers): level 0 (W x H codes, row pitch N = the padded power-of-two
// side) at src_base, levels 1..n written at pyr_base + level_off[k]; only the ancestors of the
// dirty rectangle (x0, y0)-(x1, y1), bounds inclusive, unless it is the whole map.
struct pidm_pyr {
    uint64_t src_base;     // level 0, a multiple of the AXI data width in bytes
    uint64_t pyr_base;     // the pyramid image, the same alignment
    uint32_t width;        // W, 1 .. 2^PYR.INFO.max_lg
    uint32_t height;       // H
    int bits16;            // unorm16 codes (else unorm8)
    uint32_t x0, y0, x1, y1;                  // the dirty rectangle
    uint32_t level_off[PIDM_PYR_LEVELS];      // byte offset of level k from pyr_base
};

// dm_pipeline's statistics, in register order.
enum pidm_stat {
    PIDM_STAT_CYCLES, PIDM_STAT_PIXELS, PIDM_STAT_ITERS, PIDM_STAT_H_HITS, PIDM_STAT_H_MISSES,
    PIDM_STAT_H_BYTES, PIDM_STAT_T_REQUESTS, PIDM_STAT_T_QUAD_HITS, PIDM_STAT_T_LINE_MISSES,
    PIDM_STAT_T_TEXEL_HITS, PIDM_STAT_T_BYTES, PIDM_STAT_COUNT
};
struct pidm_stats {
    uint64_t v[PIDM_STAT_COUNT];  // 48-bit counters
};

// ---- register access --------------------------------------------------------------------------
uint32_t pidm_rd(struct pidm_dev *dev, uint32_t off);
void pidm_wr(struct pidm_dev *dev, uint32_t off, uint32_t value);
void pidm_set_mmio(struct pidm_dev *dev, pidm_rd_fn rd, pidm_wr_fn wr, void *ctx);

// ---- driver -----------------------------------------------------------------------------------
// Bind dev to the register block at base (accessors: volatile loads and stores), check ID and
// VERSION, read HWCFG, mask and clear the interrupts.  PIDM_OK or PIDM_ERR_ID.
int pidm_init(struct pidm_dev *dev, volatile void *base);
// The same with accessors installed first (dev->rd, dev->wr, dev->ctx kept).
int pidm_probe(struct pidm_dev *dev);

// Apply a register write list (scripts/pack_frame.py): every offset must be TT_WRITE or in the
// configuration space (HEIGHT, SHADE, TEX) and word aligned; nothing is written otherwise.
// PIDM_ERR_BUSY while a frame runs.
int pidm_load_config(struct pidm_dev *dev, const struct pidm_reg_write *list, size_t n);
// Write triangle-table words 0 .. n-1 (word 2 t + x: triangle t, texture x), f24 in bits 23:0.
int pidm_load_triangles(struct pidm_dev *dev, const uint32_t *words, size_t n);
// Write the frame descriptor, clear INTR_STATE, start the frame.
int pidm_start(struct pidm_dev *dev, const struct pidm_frame *frame);
// Poll until the frame ends (INTR_STATE frame_done or axi_error set and STATUS.busy 0; at most
// max_polls rounds): PIDM_OK, PIDM_ERR_HW (ERROR flags set; pidm_error_flags tells which) or
// PIDM_ERR_TIMEOUT.
int pidm_poll_done(struct pidm_dev *dev, uint32_t max_polls);

// Interrupts: enable the causes in mask (PIDM_IRQ_*).
void pidm_irq_enable(struct pidm_dev *dev, uint32_t mask);
// The interrupt handler: reads INTR_STATE, clears the bits it read (write 1 to clear), adds them
// to dev->irq_seen and returns them.
uint32_t pidm_irq_handler(struct pidm_dev *dev);
// Wait for the frame-done interrupt: calls wait(ctx) (e.g. a WFI, or a simulator step that may
// run pidm_irq_handler) until dev->irq_seen has frame_done, at most max_waits times.  Consumes
// frame_done; PIDM_OK, PIDM_ERR_HW or PIDM_ERR_TIMEOUT as pidm_poll_done.
int pidm_wait_irq(struct pidm_dev *dev, void (*wait)(void *ctx), void *ctx, uint32_t max_waits);

// Statistics (read them while no frame runs: the two halves of a counter are two reads).
void pidm_read_stats(struct pidm_dev *dev, struct pidm_stats *out);
void pidm_clear_stats(struct pidm_dev *dev);
// Soft reset: abort the frame, reset the pipeline and the DMA engines; waits (max_polls reads)
// until STATUS.busy is 0.  The configuration registers keep their values.
int pidm_soft_reset(struct pidm_dev *dev, uint32_t max_polls);

// ---- the pyramid builder ---------------------------------------------------------------------
// The levels of a W x H map (n + 1: level 0 .. n, N = 2^n >= max(W, H)), and each level's byte
// offset in the pyramid image (model.heightmap.Pyramid.level_offsets(): every level's size
// rounded up to 64 bytes) into off[0 .. n], 0 above; 0 when W or H is 0 or above 2^15.
unsigned pidm_pyr_offsets(uint32_t width, uint32_t height, int bits16,
                          uint32_t off[PIDM_PYR_LEVELS]);
// Fill p's level offsets and set its dirty rectangle to the whole map (a full rebuild).
void pidm_pyr_full(struct pidm_pyr *p);
// Write the PYR registers, clear INTR_STATE.pyr_done and axi_error, pulse CTRL.pyr_start.
// PIDM_ERR_BUSY while a frame or a build runs; PIDM_ERR_ARG for no builder (PYR.INFO.present
// 0), a size above 2^PYR.INFO.max_lg, or an empty rectangle or one outside the map.
int pidm_pyr_start(struct pidm_dev *dev, const struct pidm_pyr *p);
// Poll until the build ends (INTR_STATE pyr_done, or axi_error for a refused start, and
// STATUS.pyr_busy 0): PIDM_OK, PIDM_ERR_HW (ERROR flags set: pyr_read, pyr_write, pyr_config,
// start_refused) or PIDM_ERR_TIMEOUT.
int pidm_pyr_poll_done(struct pidm_dev *dev, uint32_t max_polls);
// pidm_pyr_start, then pidm_pyr_poll_done.
int pidm_pyr_build(struct pidm_dev *dev, const struct pidm_pyr *p, uint32_t max_polls);

// Errors: the ERROR flags, clearing them, and their names ("h_axi t_axi ..." into buf).
uint32_t pidm_error_flags(struct pidm_dev *dev);
void pidm_clear_errors(struct pidm_dev *dev, uint32_t flags);
size_t pidm_error_string(uint32_t flags, char *buf, size_t len);
const char *pidm_strerror(int rc);

#ifdef __cplusplus
}
#endif

#endif  // PIDM_H
