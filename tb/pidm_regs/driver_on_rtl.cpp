// SPDX-License-Identifier: Apache-2.0
// The C driver (sw/pidm.c, compiled as C) on the RTL register block: its register accesses go
// through pidm_set_mmio accessors that run AXI4-Lite transactions on the Verilator model of
// tb/pidm_regs/pidm_regs_tb.sv (the generated pidm_regs with pidm_cfg behind it), as a CPU would.
// The "hardware" around it is played here: a start pulse makes the frame busy for a few dozen
// clocks, then frame_done (and, when asked, an error flag with axi_error); soft reset ends it.
//
// Checks: pidm_init's ID / VERSION / HWCFG; pidm_load_config of a packed frame (frame_regs.h from
// scripts/pack_frame.py) gives exactly the cfg_* port values, triangle-table writes and
// level-table writes (lvt_we_o, one per HEIGHT.LEVEL_OFF, TEX[x].LEVEL_OFF / LEVEL_SIZE write)
// expected.h lists, in order (tb/harness/pipeline_words.config, written by
// tb/pidm_regs/test_driver_on_rtl.py); pidm_start's
// descriptor reaches the ports with one start pulse; pidm_poll_done, pidm_wait_irq with the
// interrupt line, an error frame, statistics, clear statistics, soft reset mid-frame.
// Prints "driver_on_rtl: N checks, F failed"; exit status 1 when F > 0.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "Vpidm_regs_tb.h"
#include "verilated.h"

#include "pidm.h"
#include "frame_regs.h"

namespace {

unsigned checks = 0, failures = 0;

void check(bool ok, const char* what) {
  checks++;
  if (!ok) {
    failures++;
    std::fprintf(stderr, "check failed: %s\n", what);
  }
}

struct Sim {
  std::unique_ptr<VerilatedContext> ctx{new VerilatedContext};
  std::unique_ptr<Vpidm_regs_tb> m{new Vpidm_regs_tb{ctx.get()}};
  uint64_t cycle = 0;
  int busy_left = -1;       // clocks until the running frame ends (-1: no frame)
  uint32_t end_errors = 0;  // ERROR flags the running frame ends with
  unsigned starts = 0, soft_resets = 0, clears = 0;
  std::vector<std::pair<uint32_t, uint32_t>> tt;   // table writes seen on tt_we_o
  std::vector<std::pair<uint32_t, uint32_t>> lvt;  // level-table writes seen on lvt_we_o

  // One clock: inputs are set before; the edge; the hardware reacts to the outputs after it.
  void tick() {
    m->clk_i = 0;
    m->eval();
    m->clk_i = 1;
    m->eval();
    cycle++;
    m->intr_event_i = 0;
    m->error_set_i = 0;
    if (m->tt_we_o) tt.emplace_back(m->tt_waddr_o, m->tt_wdata_o);
    if (m->lvt_we_o) lvt.emplace_back(m->lvt_waddr_o, m->lvt_wdata_o);
    if (m->clear_stats_o) clears++;
    if (m->soft_reset_o) {
      soft_resets++;
      busy_left = -1;
      m->busy_i = 0;
      m->idle_i = 1;
    } else if (m->start_o) {
      starts++;
      busy_left = 40;
      m->busy_i = 1;
      m->idle_i = 0;
    } else if (busy_left > 0 && --busy_left == 0) {
      busy_left = -1;
      m->busy_i = 0;
      m->idle_i = 1;
      m->intr_event_i = 1u | (end_errors ? 2u : 0u);
      m->error_set_i = end_errors;
    }
    m->eval();
  }

  void reset() {
    m->rst_ni = 0;
    m->s_axil_awvalid = m->s_axil_wvalid = m->s_axil_arvalid = 0;
    m->s_axil_bready = m->s_axil_rready = 0;
    m->s_axil_awprot = m->s_axil_arprot = 0;
    m->busy_i = 0;
    m->idle_i = 1;
    m->hwcfg_i = 20u | (16u << 8) | (32u << 16) | (8u << 24);
    for (int i = 0; i < 5; i++) tick();
    m->rst_ni = 1;
    tick();
  }

  // AXI4-Lite write: address and data together, then the response.
  void write(uint32_t addr, uint32_t data) {
    m->s_axil_awaddr = addr;
    m->s_axil_awvalid = 1;
    m->s_axil_wdata = data;
    m->s_axil_wstrb = 0xF;
    m->s_axil_wvalid = 1;
    m->s_axil_bready = 1;
    bool aw = false, w = false;
    for (int i = 0; i < 64; i++) {
      m->eval();
      bool aw_hs = m->s_axil_awvalid && m->s_axil_awready;
      bool w_hs = m->s_axil_wvalid && m->s_axil_wready;
      bool b_hs = m->s_axil_bvalid;
      uint32_t bresp = m->s_axil_bresp;
      tick();
      if (aw_hs) { aw = true; m->s_axil_awvalid = 0; }
      if (w_hs) { w = true; m->s_axil_wvalid = 0; }
      if (b_hs && aw && w) {
        m->s_axil_bready = 0;
        check(bresp == 0, "write response OKAY");
        return;
      }
    }
    check(false, "write completes");
  }

  uint32_t read(uint32_t addr) {
    m->s_axil_araddr = addr;
    m->s_axil_arvalid = 1;
    m->s_axil_rready = 1;
    bool ar = false;
    for (int i = 0; i < 64; i++) {
      m->eval();
      bool ar_hs = m->s_axil_arvalid && m->s_axil_arready;
      bool r_hs = m->s_axil_rvalid;
      uint32_t data = m->s_axil_rdata, rresp = m->s_axil_rresp;
      tick();
      if (ar_hs) { ar = true; m->s_axil_arvalid = 0; }
      if (r_hs && ar) {
        m->s_axil_rready = 0;
        check(rresp == 0, "read response OKAY");
        return data;
      }
    }
    check(false, "read completes");
    return 0;
  }
};

uint32_t sim_rd(struct pidm_dev* dev, uint32_t off) { return static_cast<Sim*>(dev->ctx)->read(off); }
void sim_wr(struct pidm_dev* dev, uint32_t off, uint32_t v) { static_cast<Sim*>(dev->ctx)->write(off, v); }

Sim* wait_sim;
struct pidm_dev* wait_dev;
unsigned irqs;
void wait_hook(void*) {  // a CPU waiting for its interrupt line, the ISR runs when it rises
  for (int i = 0; i < 4; i++) wait_sim->tick();
  if (wait_sim->m->intr_o) {
    irqs++;
    pidm_irq_handler(wait_dev);
  }
}

bool port_equals(const uint32_t* got, const uint32_t* want, unsigned words) {
  return std::memcmp(got, want, 4 * words) == 0;
}

}  // namespace

#include "expected.h"  // check_ports(): uses check() and port_equals() above

int main(int argc, char** argv) {
  Sim s;
  s.ctx->commandArgs(argc, argv);
  s.reset();
  struct pidm_dev dev;
  std::memset(&dev, 0, sizeof dev);
  pidm_set_mmio(&dev, sim_rd, sim_wr, &s);
  check(pidm_probe(&dev) == PIDM_OK, "pidm_probe");
  check(dev.hwcfg == s.m->hwcfg_i, "HWCFG read");

  // Configuration and triangle table from the packed frame.
  check(pidm_load_config(&dev, pidm_frame_config, PIDM_FRAME_CONFIG_COUNT) == PIDM_OK,
        "pidm_load_config");
  for (int i = 0; i < 3; i++) s.tick();
  check_ports(s.m.get());  // expected.h: every cfg_* port against the pipeline harness's value
  check(s.tt.size() == EXPECTED_TT_COUNT, "table write count");
  for (size_t i = 0; i < s.tt.size() && i < EXPECTED_TT_COUNT; i++)
    check(s.tt[i].first == EXPECTED_TT[i][0] && s.tt[i].second == EXPECTED_TT[i][1],
          "table write address and data");
  check(s.lvt.size() == EXPECTED_LVT_COUNT, "level-table write count");
  for (size_t i = 0; i < s.lvt.size() && i < EXPECTED_LVT_COUNT; i++)
    check(s.lvt[i].first == EXPECTED_LVT[i][0] && s.lvt[i].second == EXPECTED_LVT[i][1],
          "level-table write address and data");

  // A frame by polling.
  check(pidm_start(&dev, &pidm_frame_desc) == PIDM_OK, "pidm_start");
  check(s.starts == 1, "one start pulse");
  check(s.m->frag_base_o == pidm_frame_desc.frag_base, "FRAG_BASE");
  check(s.m->frag_count_o == pidm_frame_desc.frag_count, "FRAG_COUNT");
  check(s.m->fb_base_o == pidm_frame_desc.fb_base, "FB_BASE");
  check(s.m->fb_pitch_o == pidm_frame_desc.fb_pitch, "FB_PITCH");
  check(s.m->status_base_o == pidm_frame_desc.status_base, "STATUS_BASE");
  check(s.m->xbits_o == pidm_frame_desc.xbits, "FB_LAYOUT.xbits");
  check(s.m->status_en_o == (pidm_frame_desc.status_en ? 1u : 0u), "FB_LAYOUT.status_en");
  check(pidm_start(&dev, &pidm_frame_desc) == PIDM_ERR_BUSY && s.starts == 1, "no start while busy");
  check(pidm_poll_done(&dev, 1000) == PIDM_OK, "pidm_poll_done");
  check(s.busy_left == -1, "the frame ended");

  // A frame by interrupt.
  pidm_irq_enable(&dev, PIDM_IRQ_ALL);
  wait_sim = &s;
  wait_dev = &dev;
  check(pidm_start(&dev, &pidm_frame_desc) == PIDM_OK, "pidm_start (irq)");
  check(s.m->intr_o == 0, "no interrupt at the start");
  check(pidm_wait_irq(&dev, wait_hook, nullptr, 1000) == PIDM_OK, "pidm_wait_irq");
  check(irqs == 1 && s.m->intr_o == 0, "one interrupt, cleared by the handler");

  // A frame that ends on an error: the interrupt carries axi_error too.
  s.end_errors = 0x2;  // t_axi
  check(pidm_start(&dev, &pidm_frame_desc) == PIDM_OK, "pidm_start (error)");
  check(pidm_wait_irq(&dev, wait_hook, nullptr, 1000) == PIDM_ERR_HW, "error frame");
  check((dev.irq_seen & PIDM_IRQ_AXI_ERROR) != 0, "axi_error interrupt seen");
  uint32_t fl = pidm_error_flags(&dev);
  char buf[64];
  pidm_error_string(fl, buf, sizeof buf);
  check(fl == 0x2 && std::strcmp(buf, "t_axi") == 0, "ERROR.t_axi");
  pidm_clear_errors(&dev, fl);
  check(pidm_error_flags(&dev) == 0, "ERROR cleared");
  s.end_errors = 0;
  pidm_irq_enable(&dev, 0);

  // Statistics.
  uint64_t want[PIDM_STAT_COUNT];
  for (unsigned i = 0; i < PIDM_STAT_COUNT; i++) {
    want[i] = (0x0000A5A5F00Dull * (i + 1) + 0x123456789ull) & 0xFFFFFFFFFFFFull;
    for (unsigned b = 0; b < 48; b++) {
      unsigned bit = 48 * i + b;
      uint32_t& word = s.m->stats_i.data()[bit / 32];
      word = (word & ~(1u << (bit % 32))) | (uint32_t((want[i] >> b) & 1u) << (bit % 32));
    }
  }
  struct pidm_stats st;
  pidm_read_stats(&dev, &st);
  for (unsigned i = 0; i < PIDM_STAT_COUNT; i++) check(st.v[i] == want[i], "statistic");
  pidm_clear_stats(&dev);
  check(s.clears == 1, "clear_stats pulse");

  // Soft reset in the middle of a frame.
  check(pidm_start(&dev, &pidm_frame_desc) == PIDM_OK, "pidm_start (soft reset)");
  for (int i = 0; i < 5; i++) s.tick();
  check(pidm_soft_reset(&dev, 100) == PIDM_OK && s.soft_resets == 1, "pidm_soft_reset");
  check(s.busy_left == -1 && s.m->busy_i == 0, "not busy after the soft reset");

  s.m->final();
  std::printf("driver_on_rtl: %u checks, %u failed (%llu clocks)\n", checks, failures,
              static_cast<unsigned long long>(s.cycle));
  return failures ? 1 : 0;
}
