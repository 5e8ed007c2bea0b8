// SPDX-License-Identifier: Apache-2.0
// Host-side unit test of the pidm driver (sw/pidm.c): the driver runs against a register file in
// memory (fake MMIO through pidm_set_mmio) that behaves as rtl/top/pidm_regs.rdl says for the
// registers the driver touches (ID, VERSION, HWCFG, PYR.INFO reset values; CTRL single pulses;
// STATUS.busy and STATUS.pyr_busy falling after a number of reads; INTR_STATE and ERROR
// write-1-to-clear).  Every write is
// logged, and the tests check the exact byte offsets and values against the documented map
// (docs/registers.md), not against the generated header the driver uses.
// Built and run by tests/test_sw_driver.py (cc -Wall -Wextra -Werror -std=c11); exit 0 when every
// check passes.
#include <stdio.h>
#include <string.h>

#include "pidm.h"

// ---- the simulated register file ----------------------------------------------------------------
#define NWORDS (0x700 / 4)
#define LOG_MAX 256

struct sim {
    uint32_t reg[NWORDS];
    uint32_t log_off[LOG_MAX], log_val[LOG_MAX];
    unsigned nlog, nreads;
    int busy_reads;        // STATUS reads left while busy (-1: not busy)
    uint32_t end_errors;   // ERROR flags the running frame ends with
    int pyr_reads;         // reads left while a pyramid build runs (-1: none)
    uint32_t pyr_errors;   // ERROR flags the build ends with
    unsigned starts, soft_resets, clears, pyr_starts;
};

// Time passes with every read: a running frame ends after busy_reads reads (of any register).
static uint32_t sim_rd(struct pidm_dev *dev, uint32_t off) {
    struct sim *s = dev->ctx;
    s->nreads++;
    if (s->busy_reads > 0 && --s->busy_reads == 0) {
        s->busy_reads = -1;
        s->reg[0x020 / 4] |= 1u;                        // INTR_STATE.frame_done
        if (s->end_errors) {
            s->reg[0x018 / 4] |= s->end_errors;         // ERROR (hwset)
            s->reg[0x020 / 4] |= 2u;                    // INTR_STATE.axi_error
        }
    }
    if (s->pyr_reads > 0 && --s->pyr_reads == 0) {
        s->pyr_reads = -1;
        s->reg[0x020 / 4] |= 4u;                        // INTR_STATE.pyr_done
        if (s->pyr_errors) {
            s->reg[0x018 / 4] |= s->pyr_errors;
            s->reg[0x020 / 4] |= 2u;
        }
    }
    if (off == 0x014)  // STATUS: busy, idle, pyr_busy
        return (s->busy_reads > 0 ? 1u : 0u) | (s->busy_reads > 0 ? 0u : 2u)
               | (s->pyr_reads > 0 ? 4u : 0u);
    return s->reg[off / 4];
}

static void sim_wr(struct pidm_dev *dev, uint32_t off, uint32_t v) {
    struct sim *s = dev->ctx;
    if (s->nlog < LOG_MAX) {
        s->log_off[s->nlog] = off;
        s->log_val[s->nlog] = v;
    }
    s->nlog++;
    switch (off) {
    case 0x000: case 0x004: case 0x008: case 0x014: case 0x01C: case 0x600: break;  // read-only
    case 0x010:  // CTRL: single pulses, read back 0
        if (v & 1u) { s->starts++; if (s->busy_reads < 0) s->busy_reads = 5; }
        if (v & 2u) { s->soft_resets++; s->busy_reads = -1; }
        if (v & 4u) s->clears++;
        if (v & 8u) { s->pyr_starts++; if (s->pyr_reads < 0) s->pyr_reads = 4; }
        break;
    case 0x018: case 0x020: s->reg[off / 4] &= ~v; break;  // W1C
    case 0x028: s->reg[0x020 / 4] |= v & 7u; break;        // INTR_TEST
    default: s->reg[off / 4] = v;
    }
}

static void sim_reset(struct sim *s) {
    memset(s, 0, sizeof *s);
    s->reg[0x000 / 4] = 0x5049444Du;
    s->reg[0x004 / 4] = 0x00010002u;
    s->reg[0x008 / 4] = 20u | (16u << 8) | (32u << 16) | (8u << 24);  // PIX_W, TRIS, ADDR_W, bytes
    s->reg[0x600 / 4] = 1u | (10u << 4);                               // PYR.INFO: present, 1024
    s->busy_reads = -1;
    s->pyr_reads = -1;
}

static void sim_clear_log(struct sim *s) { s->nlog = 0; s->nreads = 0; }

// ---- checks -----------------------------------------------------------------------------------
static unsigned checks, failures;

#define CHECK(cond) do { checks++; if (!(cond)) { failures++; \
    fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); } } while (0)

// The log must be exactly these (offset, value) pairs.
static void check_log(const struct sim *s, const uint32_t (*want)[2], unsigned n, int line) {
    checks++;
    int ok = s->nlog == n;
    for (unsigned i = 0; ok && i < n; i++)
        ok = s->log_off[i] == want[i][0] && s->log_val[i] == want[i][1];
    if (!ok) {
        failures++;
        fprintf(stderr, "%s:%d: write log differs: got %u writes:", __FILE__, line, s->nlog);
        for (unsigned i = 0; i < s->nlog && i < LOG_MAX; i++)
            fprintf(stderr, " [0x%03x]=0x%08x", (unsigned)s->log_off[i], (unsigned)s->log_val[i]);
        fprintf(stderr, "\n");
    }
}
#define CHECK_LOG(s, ...) do { static const uint32_t w_[][2] = {__VA_ARGS__}; \
    check_log((s), w_, (unsigned)(sizeof w_ / sizeof w_[0]), __LINE__); } while (0)

static struct pidm_dev *wait_dev;
static unsigned waits;
static void wait_hook(void *ctx) {  // the interrupt arrives while the CPU waits
    (void)ctx;
    waits++;
    pidm_irq_handler(wait_dev);  // its read of INTR_STATE lets the simulated frame advance
}

static void test_offsets(void) {
    // The generated header's layout equals the documented map.
    CHECK(PIDM_OFF(CTRL) == 0x010 && PIDM_OFF(STATUS) == 0x014 && PIDM_OFF(ERROR) == 0x018);
    CHECK(PIDM_OFF(INTR_STATE) == 0x020 && PIDM_OFF(INTR_ENABLE) == 0x024);
    CHECK(PIDM_OFF(INTR_TEST) == 0x028 && PIDM_OFF(FRAME) == 0x040 && PIDM_OFF(STATS) == 0x080);
    CHECK(PIDM_OFF(TT_WRITE) == 0x100 && PIDM_OFF(HEIGHT) == 0x200 && PIDM_OFF(SHADE) == 0x300);
    CHECK(PIDM_OFF(HEIGHT.LEVEL_OFF[3]) == 0x24C && PIDM_OFF(SHADE.LIGHT_X) == 0x320);
    CHECK(PIDM_OFF(TEX[1].LEVEL_SIZE[2]) == 0x588 && PIDM_OFF(TEX[0].LEVEL_OFF[0]) == 0x440);
    CHECK(PIDM_OFF(PYR) == 0x600 && PIDM_OFF(PYR.SRC_BASE) == 0x610 && PIDM_OFF(PYR.PYR_BASE) == 0x618);
    CHECK(PIDM_OFF(PYR.DIRTY1) == 0x624 && PIDM_OFF(PYR.LEVEL_OFF[15]) == 0x67C);
    CHECK(sizeof(pidm_regs_t) == 0x680);
}

static void test_init(struct sim *s, struct pidm_dev *dev) {
    sim_reset(s);
    memset(dev, 0, sizeof *dev);
    pidm_set_mmio(dev, sim_rd, sim_wr, s);
    s->reg[0x020 / 4] = 7u;  // stale causes from before
    CHECK(pidm_probe(dev) == PIDM_OK);
    CHECK(dev->hwcfg == s->reg[0x008 / 4]);
    CHECK_LOG(s, {0x024, 0}, {0x020, 7});
    CHECK(s->reg[0x020 / 4] == 0);

    struct pidm_dev bad = {0};
    struct sim s2;
    sim_reset(&s2);
    s2.reg[0] = 0x12345678u;
    pidm_set_mmio(&bad, sim_rd, sim_wr, &s2);
    CHECK(pidm_probe(&bad) == PIDM_ERR_ID && s2.nlog == 0);
    sim_reset(&s2);
    s2.reg[1] = 0x00020000u;  // major 2
    CHECK(pidm_probe(&bad) == PIDM_ERR_ID && s2.nlog == 0);

    // The plain MMIO path: volatile accesses to memory at base.
    static uint32_t mem[NWORDS];
    mem[0] = 0x5049444Du;
    mem[1] = 0x00010003u;
    mem[2] = 0xABCDu;
    mem[0x020 / 4] = 0;
    struct pidm_dev d3;
    CHECK(pidm_init(&d3, mem) == PIDM_OK && d3.hwcfg == 0xABCDu && mem[0x020 / 4] == 7u);
    CHECK(pidm_init(&d3, NULL) == PIDM_ERR_ARG);
}

static void test_config(struct sim *s, struct pidm_dev *dev) {
    static const struct pidm_reg_write list[] = {
        {0x200, 0x00000047}, {0x204, 0x01000100}, {0x240, 0}, {0x27C, 0x1234}, {0x320, 0x3e8000},
        {0x5FC, 7}, {0x100, 0x05000001},
    };
    sim_clear_log(s);
    CHECK(pidm_load_config(dev, list, 7) == PIDM_OK);
    CHECK_LOG(s, {0x200, 0x47}, {0x204, 0x01000100}, {0x240, 0}, {0x27C, 0x1234},
              {0x320, 0x3e8000}, {0x5FC, 7}, {0x100, 0x05000001});
    // Nothing outside the configuration space, nothing unaligned, nothing past the map.
    static const struct pidm_reg_write ctrl[] = {{0x200, 1}, {0x010, 1}};
    static const struct pidm_reg_write unal[] = {{0x202, 1}};
    static const struct pidm_reg_write past[] = {{0x600, 1}};
    static const struct pidm_reg_write frame[] = {{0x040, 1}};
    sim_clear_log(s);
    CHECK(pidm_load_config(dev, ctrl, 2) == PIDM_ERR_ARG);
    CHECK(pidm_load_config(dev, unal, 1) == PIDM_ERR_ARG);
    CHECK(pidm_load_config(dev, past, 1) == PIDM_ERR_ARG);
    CHECK(pidm_load_config(dev, frame, 1) == PIDM_ERR_ARG);
    CHECK(pidm_load_config(dev, NULL, 1) == PIDM_ERR_ARG);
    CHECK(s->nlog == 0);
    // Not while a frame runs.
    s->busy_reads = 100;
    CHECK(pidm_load_config(dev, list, 1) == PIDM_ERR_BUSY && s->nlog == 0);
    s->busy_reads = -1;
}

static void test_triangles(struct sim *s, struct pidm_dev *dev) {
    static const uint32_t words[] = {0x3f0000, 0xFF3e8000, 0xbf1234};
    sim_clear_log(s);
    CHECK(pidm_load_triangles(dev, words, 3) == PIDM_OK);
    CHECK_LOG(s, {0x100, 0x003f0000}, {0x100, 0x013e8000}, {0x100, 0x02bf1234});
    static uint32_t many[33];
    sim_clear_log(s);
    CHECK(pidm_load_triangles(dev, many, 33) == PIDM_ERR_ARG);  // HWCFG.tris = 16: 32 words
    CHECK(pidm_load_triangles(dev, many, 32) == PIDM_OK && s->nlog == 32);
    CHECK(s->log_val[31] == (31u << 24));
}

static const struct pidm_frame FRAME = {
    .frag_base = 0x0000000160000000ull, .frag_count = 4096, .fb_base = 0x70000040ull,
    .fb_pitch = 256, .xbits = 6, .status_base = 0x0000000278000000ull, .status_en = 1,
};

static void test_start_poll(struct sim *s, struct pidm_dev *dev) {
    sim_clear_log(s);
    CHECK(pidm_start(dev, &FRAME) == PIDM_OK);
    CHECK_LOG(s, {0x040, 0x60000000}, {0x044, 0x1}, {0x048, 4096}, {0x04C, 256},
              {0x050, 0x70000040}, {0x054, 0}, {0x058, 0x78000000}, {0x05C, 0x2},
              {0x060, 0x106}, {0x020, 3}, {0x010, 1});
    CHECK(s->starts == 1);
    // Running: a second start is refused without a write.
    sim_clear_log(s);
    CHECK(pidm_start(dev, &FRAME) == PIDM_ERR_BUSY && s->nlog == 0);
    // Poll: busy for the rest of the 5 reads, then done without error.
    CHECK(pidm_poll_done(dev, 100) == PIDM_OK);
    CHECK(s->reg[0x020 / 4] == 1u);  // frame_done raised (not enabled, so no interrupt)
    // A timeout.
    sim_clear_log(s);
    CHECK(pidm_start(dev, &FRAME) == PIDM_OK);
    CHECK(pidm_poll_done(dev, 2) == PIDM_ERR_TIMEOUT);
    CHECK(pidm_poll_done(dev, 100) == PIDM_OK);
    // A frame that ends on errors.
    s->end_errors = (1u << 1) | (1u << 3);
    CHECK(pidm_start(dev, &FRAME) == PIDM_OK);
    CHECK(pidm_poll_done(dev, 100) == PIDM_ERR_HW);
    uint32_t fl = pidm_error_flags(dev);
    CHECK(fl == 0xAu);
    char buf[64];
    CHECK(pidm_error_string(fl, buf, sizeof buf) == strlen("t_axi fb_write"));
    CHECK(strcmp(buf, "t_axi fb_write") == 0);
    sim_clear_log(s);
    pidm_clear_errors(dev, fl);
    CHECK_LOG(s, {0x018, 0xA});
    CHECK(pidm_error_flags(dev) == 0);
    s->end_errors = 0;
    // A start the hardware refuses (bad configuration): no busy, ERROR.bad_config and
    // INTR_STATE.axi_error at once; the poll ends with the error.
    s->reg[0x018 / 4] = 0x10u;
    s->reg[0x020 / 4] = 0x2u;
    CHECK(pidm_poll_done(dev, 1) == PIDM_ERR_HW);
    pidm_clear_errors(dev, 0x10u);
    // Busy not yet visible after the start: without frame_done / axi_error the poll waits.
    s->reg[0x020 / 4] = 0;
    CHECK(pidm_poll_done(dev, 50) == PIDM_ERR_TIMEOUT);
    // Bad descriptor.
    struct pidm_frame f = FRAME;
    f.xbits = 32;
    CHECK(pidm_start(dev, &f) == PIDM_ERR_ARG);
}

static void test_irq(struct sim *s, struct pidm_dev *dev) {
    sim_clear_log(s);
    pidm_irq_enable(dev, PIDM_IRQ_ALL | 0x100u);
    CHECK_LOG(s, {0x024, 7});
    // The handler reads INTR_STATE and clears exactly what it read.
    s->reg[0x020 / 4] = 2u;
    sim_clear_log(s);
    CHECK(pidm_irq_handler(dev) == 2u);
    CHECK_LOG(s, {0x020, 2});
    CHECK(s->reg[0x020 / 4] == 0 && (dev->irq_seen & 2u));
    sim_clear_log(s);
    CHECK(pidm_irq_handler(dev) == 0 && s->nlog == 0);  // nothing pending: no write
    // A frame waited for by interrupt: the hook runs the handler as the interrupt would.
    wait_dev = dev;
    waits = 0;
    CHECK(pidm_start(dev, &FRAME) == PIDM_OK);
    CHECK(pidm_wait_irq(dev, wait_hook, NULL, 100) == PIDM_OK);
    CHECK(waits == 5 && !(dev->irq_seen & PIDM_IRQ_FRAME_DONE));
    CHECK(s->reg[0x020 / 4] == 0);
    // No interrupt comes: timeout.
    CHECK(pidm_wait_irq(dev, wait_hook, NULL, 3) == PIDM_ERR_TIMEOUT);
    CHECK(pidm_wait_irq(dev, NULL, NULL, 3) == PIDM_ERR_ARG);
    // INTR_TEST through the simulated block raises the cause the handler then sees.
    pidm_wr(dev, 0x028, 1u);
    CHECK(pidm_irq_handler(dev) == 1u);
}

static void test_stats_reset(struct sim *s, struct pidm_dev *dev) {
    for (unsigned i = 0; i < PIDM_STAT_COUNT; i++) {
        s->reg[(0x080 + 8 * i) / 4] = 0x89ABCDEFu ^ i;
        s->reg[(0x084 + 8 * i) / 4] = 0x1234u + i;
    }
    s->reg[0x084 / 4] |= 0xFFFF0000u;  // bits above 47 read as 0 in hardware; masked anyway
    struct pidm_stats st;
    sim_clear_log(s);
    unsigned r0 = s->nreads;
    pidm_read_stats(dev, &st);
    CHECK(s->nlog == 0 && s->nreads - r0 == 2 * PIDM_STAT_COUNT);
    CHECK(st.v[PIDM_STAT_CYCLES] == 0x123489ABCDEFull);
    CHECK(st.v[PIDM_STAT_T_BYTES] == (((uint64_t)(0x1234u + 10) << 32) | (0x89ABCDEFu ^ 10u)));
    sim_clear_log(s);
    pidm_clear_stats(dev);
    CHECK_LOG(s, {0x010, 4});
    CHECK(s->clears == 1);
    // Soft reset mid-frame: busy falls.
    CHECK(pidm_start(dev, &FRAME) == PIDM_OK);
    sim_clear_log(s);
    CHECK(pidm_soft_reset(dev, 10) == PIDM_OK);
    CHECK_LOG(s, {0x010, 2});
    CHECK(s->soft_resets == 1 && s->busy_reads == -1);
}

static void test_pyr(struct sim *s, struct pidm_dev *dev) {
    // Level offsets as model.heightmap.Pyramid.level_offsets(): 100 x 60 unorm8 pads to 128.
    uint32_t off[PIDM_PYR_LEVELS];
    CHECK(pidm_pyr_offsets(100, 60, 0, off) == 8);
    CHECK(off[0] == 0 && off[1] == 16384 && off[2] == 16384 + 4096 && off[3] == 21504);
    CHECK(off[6] == 21504 + 256 + 64 + 64 && off[7] == off[6] + 64 && off[8] == 0);
    CHECK(pidm_pyr_offsets(1, 1, 1, off) == 1 && off[0] == 0 && off[1] == 0);
    CHECK(pidm_pyr_offsets(3, 2, 1, off) == 3 && off[1] == 64 && off[2] == 128);
    CHECK(pidm_pyr_offsets(0, 4, 0, off) == 0 && pidm_pyr_offsets(1u << 16, 4, 0, off) == 0);
    // A full build of 100 x 60 unorm16 at two 64-bit bases.
    struct pidm_pyr p = {.src_base = 0x0000000180000000ull, .pyr_base = 0x90000040ull,
                         .width = 100, .height = 60, .bits16 = 1};
    pidm_pyr_full(&p);
    CHECK(p.x0 == 0 && p.y0 == 0 && p.x1 == 99 && p.y1 == 59 && p.level_off[1] == 32768);
    sim_clear_log(s);
    CHECK(pidm_pyr_start(dev, &p) == PIDM_OK);
    CHECK(s->nlog == 10 + PIDM_PYR_LEVELS && s->pyr_starts == 1);
    CHECK_LOG(s, {0x604, 1}, {0x608, 100u | (60u << 16)}, {0x610, 0x80000000}, {0x614, 1},
              {0x618, 0x90000040}, {0x61C, 0}, {0x620, 0}, {0x624, 99u | (59u << 16)},
              {0x640, 0}, {0x644, 32768}, {0x648, 32768 + 8192}, {0x64C, 43008},
              {0x650, 43008 + 512}, {0x654, 43008 + 512 + 128}, {0x658, 43008 + 512 + 192},
              {0x65C, 43008 + 512 + 256}, {0x660, 0}, {0x664, 0}, {0x668, 0}, {0x66C, 0},
              {0x670, 0}, {0x674, 0}, {0x678, 0}, {0x67C, 0}, {0x020, 6}, {0x010, 8});
    // Running: a frame or another build is refused without a write.
    sim_clear_log(s);
    CHECK(pidm_pyr_start(dev, &p) == PIDM_ERR_BUSY && s->nlog == 0);
    CHECK(pidm_pyr_poll_done(dev, 100) == PIDM_OK);
    CHECK(s->reg[0x020 / 4] == 4u);  // pyr_done raised
    // A dirty rectangle, a build that ends on a write error, a timeout.
    p.x0 = 10; p.y0 = 20; p.x1 = 10; p.y1 = 31;
    s->pyr_errors = 1u << 6;
    sim_clear_log(s);
    CHECK(pidm_pyr_build(dev, &p, 100) == PIDM_ERR_HW);
    CHECK(s->log_val[6] == (10u | (20u << 16)) && s->log_val[7] == (10u | (31u << 16)));
    CHECK(pidm_error_flags(dev) == 0x40u);
    pidm_clear_errors(dev, 0x40u);
    s->pyr_errors = 0;
    CHECK(pidm_pyr_start(dev, &p) == PIDM_OK);
    CHECK(pidm_pyr_poll_done(dev, 1) == PIDM_ERR_TIMEOUT);
    CHECK(pidm_pyr_poll_done(dev, 100) == PIDM_OK);
    // Bad arguments: nothing written.
    sim_clear_log(s);
    struct pidm_pyr q = p;
    q.x1 = 100;                        // outside the map
    CHECK(pidm_pyr_start(dev, &q) == PIDM_ERR_ARG);
    q = p; q.y0 = 32;                  // empty
    CHECK(pidm_pyr_start(dev, &q) == PIDM_ERR_ARG);
    q = p; q.width = 1025;             // above 2^PYR.INFO.max_lg
    CHECK(pidm_pyr_start(dev, &q) == PIDM_ERR_ARG);
    CHECK(pidm_pyr_start(dev, NULL) == PIDM_ERR_ARG && s->nlog == 0);
    s->reg[0x600 / 4] = 10u << 4;      // no builder in this instance
    CHECK(pidm_pyr_start(dev, &p) == PIDM_ERR_ARG && s->nlog == 0);
    s->reg[0x600 / 4] = 1u | (10u << 4);
    // A frame running: no build.
    s->busy_reads = 100;
    CHECK(pidm_pyr_start(dev, &p) == PIDM_ERR_BUSY && s->nlog == 0);
    s->busy_reads = -1;
}

static void test_strings(void) {
    char buf[64];
    CHECK(pidm_error_string(0, buf, sizeof buf) == 0 && buf[0] == '\0');
    pidm_error_string(0x1Fu | 0x1000u, buf, sizeof buf);
    CHECK(strcmp(buf, "h_axi t_axi frag_dma fb_write bad_config unknown:0x1000") == 0);
    pidm_error_string(0x1E0u, buf, sizeof buf);
    CHECK(strcmp(buf, "pyr_read pyr_write pyr_config start_refused") == 0);
    char small[8];
    size_t n = pidm_error_string(0x10u, small, sizeof small);  // truncated, still terminated
    CHECK(n == strlen("bad_config") && strcmp(small, "bad_con") == 0);
    CHECK(strcmp(pidm_strerror(PIDM_ERR_BUSY), "a frame or a pyramid build is running") == 0);
    CHECK(strcmp(pidm_strerror(42), "unknown") == 0);
}

int main(void) {
    static struct sim s;
    struct pidm_dev dev;
    test_offsets();
    test_init(&s, &dev);
    test_config(&s, &dev);
    test_triangles(&s, &dev);
    test_start_poll(&s, &dev);
    test_irq(&s, &dev);
    test_stats_reset(&s, &dev);
    test_pyr(&s, &dev);
    test_strings();
    printf("test_pidm: %u checks, %u failed\n", checks, failures);
    return failures ? 1 : 0;
}
