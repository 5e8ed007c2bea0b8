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

#define OFF_TEX_END PIDM_OFF(PYR)

static_assert(PIDM_PYR_LEVELS == sizeof(((pidm_regs_t *)0)->PYR.LEVEL_OFF) / 4, "PYR.LEVEL_OFF");

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

static int pyr_busy(struct pidm_dev *dev) {
    return (pidm_rd(dev, PIDM_OFF(STATUS)) & PIDM_REGS__STATUS__PYR_BUSY_bm) != 0;
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
    pidm_wr(dev, PIDM_OFF(INTR_STATE), PIDM_IRQ_FRAME);
    dev->irq_seen &= ~PIDM_IRQ_FRAME;
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
        uint32_t st = (pidm_rd(dev, PIDM_OFF(INTR_STATE)) | dev->irq_seen) & PIDM_IRQ_FRAME;
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

unsigned pidm_pyr_offsets(uint32_t width, uint32_t height, int bits16,
                          uint32_t off[PIDM_PYR_LEVELS]) {
    for (unsigned k = 0; k < PIDM_PYR_LEVELS; k++) off[k] = 0;
    uint32_t side = width > height ? width : height;
    if (width == 0 || height == 0 || side > (1u << (PIDM_PYR_LEVELS - 1))) return 0;
    unsigned n = 0;
    while ((1u << n) < side) n++;
    uint32_t o = 0;
    for (unsigned k = 0; k <= n; k++) {
        off[k] = o;
        uint32_t s = (1u << n) >> k;
        uint32_t bytes = s * s * (bits16 ? 2u : 1u);
        o += (bytes + 63u) & ~63u;
    }
    return n + 1;
}

void pidm_pyr_full(struct pidm_pyr *p) {
    pidm_pyr_offsets(p->width, p->height, p->bits16, p->level_off);
    p->x0 = 0;
    p->y0 = 0;
    p->x1 = p->width ? p->width - 1 : 0;
    p->y1 = p->height ? p->height - 1 : 0;
}

int pidm_pyr_start(struct pidm_dev *dev, const struct pidm_pyr *p) {
    if (!dev || !p) return PIDM_ERR_ARG;
    uint32_t info = pidm_rd(dev, PIDM_OFF(PYR.INFO));
    uint32_t max_side = 1u << ((info & PIDM_REGS__PYR__INFO__MAX_LG_bm) >> PIDM_REGS__PYR__INFO__MAX_LG_bp);
    if (!(info & PIDM_REGS__PYR__INFO__PRESENT_bm) || p->width == 0 || p->height == 0
        || p->width > max_side || p->height > max_side || p->x0 > p->x1 || p->y0 > p->y1
        || p->x1 >= p->width || p->y1 >= p->height)
        return PIDM_ERR_ARG;
    if (busy(dev) || pyr_busy(dev)) return PIDM_ERR_BUSY;
    pidm_wr(dev, PIDM_OFF(PYR.FORMAT), p->bits16 ? PIDM_REGS__PYR__FORMAT__BITS16_bm : 0u);
    pidm_wr(dev, PIDM_OFF(PYR.SIZE), (p->width << PIDM_REGS__PYR__SIZE__WIDTH_bp)
                                         | (p->height << PIDM_REGS__PYR__SIZE__HEIGHT_bp));
    wr64(dev, PIDM_OFF(PYR.SRC_BASE), p->src_base);
    wr64(dev, PIDM_OFF(PYR.PYR_BASE), p->pyr_base);
    pidm_wr(dev, PIDM_OFF(PYR.DIRTY0), (p->x0 << PIDM_REGS__PYR__DIRTY0__X0_bp)
                                           | (p->y0 << PIDM_REGS__PYR__DIRTY0__Y0_bp));
    pidm_wr(dev, PIDM_OFF(PYR.DIRTY1), (p->x1 << PIDM_REGS__PYR__DIRTY1__X1_bp)
                                           | (p->y1 << PIDM_REGS__PYR__DIRTY1__Y1_bp));
    for (unsigned k = 0; k < PIDM_PYR_LEVELS; k++)
        pidm_wr(dev, PIDM_OFF(PYR.LEVEL_OFF[k]), p->level_off[k]);
    pidm_wr(dev, PIDM_OFF(INTR_STATE), PIDM_IRQ_PYR_DONE | PIDM_IRQ_AXI_ERROR);
    dev->irq_seen &= ~(PIDM_IRQ_PYR_DONE | PIDM_IRQ_AXI_ERROR);
    pidm_wr(dev, PIDM_OFF(CTRL), PIDM_REGS__CTRL__PYR_START_bm);
    return PIDM_OK;
}

// The build has ended when it raised pyr_done (or axi_error: a start refused at once) and
// STATUS.pyr_busy is 0.
int pidm_pyr_poll_done(struct pidm_dev *dev, uint32_t max_polls) {
    if (!dev) return PIDM_ERR_ARG;
    for (uint32_t i = 0; i < max_polls; i++) {
        uint32_t st = (pidm_rd(dev, PIDM_OFF(INTR_STATE)) | dev->irq_seen)
                      & (PIDM_IRQ_PYR_DONE | PIDM_IRQ_AXI_ERROR);
        if (st && !pyr_busy(dev)) return frame_result(dev);
    }
    return PIDM_ERR_TIMEOUT;
}

int pidm_pyr_build(struct pidm_dev *dev, const struct pidm_pyr *p, uint32_t max_polls) {
    int rc = pidm_pyr_start(dev, p);
    return rc != PIDM_OK ? rc : pidm_pyr_poll_done(dev, max_polls);
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
    {PIDM_REGS__ERROR__PYR_READ_bm, "pyr_read"},
    {PIDM_REGS__ERROR__PYR_WRITE_bm, "pyr_write"},
    {PIDM_REGS__ERROR__PYR_CONFIG_bm, "pyr_config"},
    {PIDM_REGS__ERROR__START_REFUSED_bm, "start_refused"},
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
    case PIDM_ERR_BUSY: return "a frame or a pyramid build is running";
    case PIDM_ERR_HW: return "the frame ended with an error";
    case PIDM_ERR_TIMEOUT: return "timed out";
    case PIDM_ERR_ARG: return "bad argument";
    default: return "unknown";
    }
}
