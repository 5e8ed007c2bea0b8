// SPDX-License-Identifier: Apache-2.0
// pidm: the host driver of pidm_top (sw/pidm.h).
#include "pidm.h"

#include <stdio.h>
#include <string.h>

// The statistics are 8 bytes apart (LO, HI) in enum pidm_stat order.
static_assert(offsetof(pidm_regs_t, STATS.t_bytes) == offsetof(pidm_regs_t, STATS) + 8 * PIDM_STAT_T_BYTES,
              "STATS layout");
static_assert(offsetof(pidm_regs_t, STATS.h_bytes) == offsetof(pidm_regs_t, STATS) + 8 * PIDM_STAT_H_BYTES,
              "STATS layout");

#define OFF_TEX_END ((uint32_t)sizeof(pidm_regs_t))

uint32_t pidm_rd(struct pidm_dev *dev, uint32_t off) {
    if (dev->rd) return dev->rd(dev, off);
    return dev->base[off / 4u];
}

void pidm_wr(struct pidm_dev *dev, uint32_t off, uint32_t value) {
    if (dev->wr) {
        dev->wr(dev, off, value);
        return;
    }
    dev->base[off / 4u] = value;
}

void pidm_set_mmio(struct pidm_dev *dev, pidm_rd_fn rd, pidm_wr_fn wr, void *ctx) {
    dev->rd = rd;
    dev->wr = wr;
    dev->ctx = ctx;
}

int pidm_probe(struct pidm_dev *dev) {
    if (!dev) return PIDM_ERR_ARG;
    dev->irq_seen = 0;
    if (pidm_rd(dev, PIDM_OFF(ID)) != PIDM_ID_VALUE) return PIDM_ERR_ID;
    uint32_t ver = pidm_rd(dev, PIDM_OFF(VERSION));
    if (((ver & PIDM_REGS__VERSION__MAJOR_bm) >> PIDM_REGS__VERSION__MAJOR_bp) != PIDM_VERSION_MAJOR)
        return PIDM_ERR_ID;
    dev->hwcfg = pidm_rd(dev, PIDM_OFF(HWCFG));
    pidm_wr(dev, PIDM_OFF(INTR_ENABLE), 0);
    pidm_wr(dev, PIDM_OFF(INTR_STATE), PIDM_IRQ_ALL);
    return PIDM_OK;
}

int pidm_init(struct pidm_dev *dev, volatile void *base) {
    if (!dev || !base) return PIDM_ERR_ARG;
    memset(dev, 0, sizeof *dev);
    dev->base = (volatile uint32_t *)base;
    return pidm_probe(dev);
}

static int busy(struct pidm_dev *dev) {
    return (pidm_rd(dev, PIDM_OFF(STATUS)) & PIDM_REGS__STATUS__BUSY_bm) != 0;
}

static int config_offset(uint32_t off) {
    if (off & 3u) return 0;
    return off == PIDM_OFF(TT_WRITE) || (off >= PIDM_OFF(HEIGHT) && off < OFF_TEX_END);
}

int pidm_load_config(struct pidm_dev *dev, const struct pidm_reg_write *list, size_t n) {
    if (!dev || (n && !list)) return PIDM_ERR_ARG;
    for (size_t i = 0; i < n; i++)
        if (!config_offset(list[i].off)) return PIDM_ERR_ARG;
    if (busy(dev)) return PIDM_ERR_BUSY;
    for (size_t i = 0; i < n; i++) pidm_wr(dev, list[i].off, list[i].value);
    return PIDM_OK;
}

int pidm_load_triangles(struct pidm_dev *dev, const uint32_t *words, size_t n) {
    if (!dev || (n && !words)) return PIDM_ERR_ARG;
    uint32_t tris = (dev->hwcfg & PIDM_REGS__HWCFG__TRIS_bm) >> PIDM_REGS__HWCFG__TRIS_bp;
    if (n > 2u * tris || n > (PIDM_REGS__TT_WRITE__ADDR_bm >> PIDM_REGS__TT_WRITE__ADDR_bp) + 1u)
        return PIDM_ERR_ARG;
    if (busy(dev)) return PIDM_ERR_BUSY;
    for (size_t i = 0; i < n; i++)
        pidm_wr(dev, PIDM_OFF(TT_WRITE),
                (words[i] & PIDM_REGS__TT_WRITE__DATA_bm)
                    | (((uint32_t)i << PIDM_REGS__TT_WRITE__ADDR_bp) & PIDM_REGS__TT_WRITE__ADDR_bm));
    return PIDM_OK;
}

static void wr64(struct pidm_dev *dev, uint32_t off, uint64_t v) {
    pidm_wr(dev, off, (uint32_t)v);
    pidm_wr(dev, off + 4u, (uint32_t)(v >> 32));
}

int pidm_start(struct pidm_dev *dev, const struct pidm_frame *f) {
    if (!dev || !f || f->xbits > (PIDM_REGS__FRAME__FB_LAYOUT__XBITS_bm >> PIDM_REGS__FRAME__FB_LAYOUT__XBITS_bp))
        return PIDM_ERR_ARG;
    if (busy(dev)) return PIDM_ERR_BUSY;
    wr64(dev, PIDM_OFF(FRAME.FRAG_BASE), f->frag_base);
    pidm_wr(dev, PIDM_OFF(FRAME.FRAG_COUNT), f->frag_count);
    pidm_wr(dev, PIDM_OFF(FRAME.FB_PITCH), f->fb_pitch);
    wr64(dev, PIDM_OFF(FRAME.FB_BASE), f->fb_base);
    wr64(dev, PIDM_OFF(FRAME.STATUS_BASE), f->status_base);
    pidm_wr(dev, PIDM_OFF(FRAME.FB_LAYOUT),
            (f->xbits << PIDM_REGS__FRAME__FB_LAYOUT__XBITS_bp)
                | (f->status_en ? PIDM_REGS__FRAME__FB_LAYOUT__STATUS_EN_bm : 0u));
    pidm_wr(dev, PIDM_OFF(INTR_STATE), PIDM_IRQ_ALL);
    dev->irq_seen = 0;
    pidm_wr(dev, PIDM_OFF(CTRL), PIDM_REGS__CTRL__START_bm);
    return PIDM_OK;
}

static int frame_result(struct pidm_dev *dev) {
    return pidm_error_flags(dev) ? PIDM_ERR_HW : PIDM_OK;
}

// The frame has ended when it raised frame_done or axi_error (pidm_start cleared both; a bad
// configuration raises axi_error without starting) and STATUS.busy is 0: busy alone could be read
// before the start pulse has set it.
int pidm_poll_done(struct pidm_dev *dev, uint32_t max_polls) {
    if (!dev) return PIDM_ERR_ARG;
    for (uint32_t i = 0; i < max_polls; i++) {
        uint32_t st = (pidm_rd(dev, PIDM_OFF(INTR_STATE)) | dev->irq_seen) & PIDM_IRQ_ALL;
        if (st && !busy(dev)) return frame_result(dev);
    }
    return PIDM_ERR_TIMEOUT;
}

void pidm_irq_enable(struct pidm_dev *dev, uint32_t mask) {
    pidm_wr(dev, PIDM_OFF(INTR_ENABLE), mask & PIDM_IRQ_ALL);
}

uint32_t pidm_irq_handler(struct pidm_dev *dev) {
    uint32_t st = pidm_rd(dev, PIDM_OFF(INTR_STATE)) & PIDM_IRQ_ALL;
    if (st) pidm_wr(dev, PIDM_OFF(INTR_STATE), st);
    dev->irq_seen |= st;
    return st;
}

int pidm_wait_irq(struct pidm_dev *dev, void (*wait)(void *ctx), void *ctx, uint32_t max_waits) {
    if (!dev || !wait) return PIDM_ERR_ARG;
    for (uint32_t i = 0; i < max_waits; i++) {
        if (dev->irq_seen & PIDM_IRQ_FRAME_DONE) {
            dev->irq_seen &= ~PIDM_IRQ_FRAME_DONE;
            return frame_result(dev);
        }
        wait(ctx);
    }
    if (dev->irq_seen & PIDM_IRQ_FRAME_DONE) {
        dev->irq_seen &= ~PIDM_IRQ_FRAME_DONE;
        return frame_result(dev);
    }
    return PIDM_ERR_TIMEOUT;
}

void pidm_read_stats(struct pidm_dev *dev, struct pidm_stats *out) {
    for (unsigned i = 0; i < PIDM_STAT_COUNT; i++) {
        uint32_t off = PIDM_OFF(STATS) + 8u * i;
        uint64_t lo = pidm_rd(dev, off);
        uint64_t hi = pidm_rd(dev, off + 4u) & PIDM_REGS__STATS__CYCLES__HI__VAL_bm;
        out->v[i] = lo | (hi << 32);
    }
}

void pidm_clear_stats(struct pidm_dev *dev) {
    pidm_wr(dev, PIDM_OFF(CTRL), PIDM_REGS__CTRL__CLEAR_STATS_bm);
}

int pidm_soft_reset(struct pidm_dev *dev, uint32_t max_polls) {
    if (!dev) return PIDM_ERR_ARG;
    pidm_wr(dev, PIDM_OFF(CTRL), PIDM_REGS__CTRL__SOFT_RESET_bm);
    for (uint32_t i = 0; i < max_polls; i++)
        if (!busy(dev)) return PIDM_OK;
    return PIDM_ERR_TIMEOUT;
}

uint32_t pidm_error_flags(struct pidm_dev *dev) {
    return pidm_rd(dev, PIDM_OFF(ERROR));
}

void pidm_clear_errors(struct pidm_dev *dev, uint32_t flags) {
    pidm_wr(dev, PIDM_OFF(ERROR), flags);
}

static const struct {
    uint32_t mask;
    const char *name;
} error_names[] = {
    {PIDM_REGS__ERROR__H_AXI_bm, "h_axi"},
    {PIDM_REGS__ERROR__T_AXI_bm, "t_axi"},
    {PIDM_REGS__ERROR__FRAG_DMA_bm, "frag_dma"},
    {PIDM_REGS__ERROR__FB_WRITE_bm, "fb_write"},
    {PIDM_REGS__ERROR__BAD_CONFIG_bm, "bad_config"},
};

size_t pidm_error_string(uint32_t flags, char *buf, size_t len) {
    size_t used = 0;
    if (len) buf[0] = '\0';
    for (size_t i = 0; i < sizeof error_names / sizeof error_names[0]; i++) {
        if (!(flags & error_names[i].mask)) continue;
        flags &= ~error_names[i].mask;
        int k = snprintf(used < len ? buf + used : NULL, used < len ? len - used : 0, "%s%s",
                         used ? " " : "", error_names[i].name);
        used += (size_t)k;
    }
    if (flags) {
        int k = snprintf(used < len ? buf + used : NULL, used < len ? len - used : 0,
                         "%sunknown:0x%x", used ? " " : "", (unsigned)flags);
        used += (size_t)k;
    }
    return used;
}

const char *pidm_strerror(int rc) {
    switch (rc) {
    case PIDM_OK: return "ok";
    case PIDM_ERR_ID: return "not a pidm_top (ID or VERSION)";
    case PIDM_ERR_BUSY: return "a frame is running";
    case PIDM_ERR_HW: return "the frame ended with an error";
    case PIDM_ERR_TIMEOUT: return "timed out";
    case PIDM_ERR_ARG: return "bad argument";
    default: return "unknown";
    }
}
