// SPDX-License-Identifier: Apache-2.0
// system_harness: a Verilator main that plays CPU and memory for the system top pidm_top
// (rtl/top/pidm_top.sv) on a whole frame.  tb/harness/pidm_system.py builds it
// (build/harness/system/<variant>/) and drives it.
//
//   input file -> memory regions (fragment buffer on AXI port F, height pyramid on H, textures on
//                 T, framebuffer and status buffer behind the write port W) and register writes
//   CPU (AXI4-Lite): INTR_ENABLE, the configuration, the frame descriptor, CTRL.start (the input's
//                 writes, in order); then it waits for irq_o, reads INTR_STATE, ERROR, PROGRESS
//                 and the statistics registers (offsets from the generated sw/pidm_regs.h)
//   output file <- the framebuffer and the status buffer; JSON statistics
//
// File formats: system_harness.h.  Command line: --help.
//
// Checks (message on stderr, non-zero exit status): the interrupt comes before --timeout clocks
// (exit 2); INTR_STATE is frame_done alone, ERROR is 0, PROGRESS and STATS.pixels equal the
// fragment count; the read masters keep the AXI protocol (axi_mem.h); every write lands inside
// the framebuffer or the status buffer, single-beat or INCR within 4 KiB (exit 3 otherwise).
//
// Clocking: per clock, inputs are set with clk low and evaluated, the handshakes are sampled,
// then the rising edge is evaluated.  While rst_ni is low no handshake counts (the registers
// hold random initial values until the first reset edge).  The write slave takes AW and W whenever offered (with
// random stalls) and answers B after the write port's latency, in order.
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "../../sw/pidm_regs.h"
#include "Vpidm_top.h"
#include "axi_mem.h"
#include "harness_common.h"
#include "system_harness.h"
#include "verilated.h"

#ifndef HARNESS_DATA_W
#define HARNESS_DATA_W 64
#endif

namespace {

using harness::AxiMemConfig;
using harness::AxiStats;
using harness::Coin;
using harness::fail;
using harness::Rng;

constexpr unsigned kDataBytes = HARNESS_DATA_W / 8;
static_assert(kDataBytes == 8, "the harness drives 64-bit AXI data ports");
using ReadMem = harness::AxiReadSlave<kDataBytes, 64>;

const char* kUsage = R"(usage: system_harness --in FILE --out FILE [options]

Runs pidm_top (registers, fragment DMA, pipeline, framebuffer DMA) on a frame, after a pyramid
build when the input has one: the harness is the CPU (AXI4-Lite) and the memory (four AXI4
ports).

  --in FILE          input (system_harness.h)
  --out FILE         framebuffer and status buffer after the frame
  --stats FILE       JSON statistics
  --latency L        AXI read latency of every read port, L or MIN:MAX clocks (default 20)
  --w-latency L      write response latency (default 10)
  --seed N           random latencies and stalls (default 0)
  --ar-stall P       probability of arready / awready / wready low in a clock (default 0)
  --timeout N        clocks from CTRL.start to the interrupt (default 2000000 + 4000 per pixel)
  --quiet            no summary line
)";

struct Options {
  std::string in, out, stats;
  AxiMemConfig rmem;
  uint32_t w_lat = 10;
  uint64_t seed = 0, timeout = 0;
  double stall = 0;
  bool quiet = false;
};

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto val = [&]() -> std::string {
      if (i + 1 >= argc) fail(1, "%s needs a value", a.c_str());
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a == "--in") {
      o.in = val();
    } else if (a == "--out") {
      o.out = val();
    } else if (a == "--stats") {
      o.stats = val();
    } else if (a == "--latency") {
      std::tie(o.rmem.lat_min, o.rmem.lat_max) = harness::parse_latency(val(), "--latency");
    } else if (a == "--w-latency") {
      o.w_lat = harness::parse_latency(val(), "--w-latency").first;
    } else if (a == "--seed") {
      o.seed = harness::parse_u64(val(), "--seed");
    } else if (a == "--ar-stall") {
      o.stall = harness::parse_prob(val(), "--ar-stall");
    } else if (a == "--timeout") {
      o.timeout = harness::parse_u64(val(), "--timeout");
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      fail(1, "unknown option %s (--help)", a.c_str());
    }
  }
  if (o.in.empty() || o.out.empty()) fail(1, "--in and --out are required (--help)");
  o.rmem.ar_stall = o.stall;
  return o;
}

struct Region {
  uint32_t port = 0, base = 0;
  std::vector<uint8_t> data;
};

struct Input {
  sysh::InHeader h{};
  std::vector<Region> regions;
  std::vector<sysh::RegWrite> writes;
};

Input read_input(const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) fail(1, "cannot read %s: %s", path.c_str(), std::strerror(errno));
  Input in;
  auto rd = [&](void* p, size_t n) {
    if (n && std::fread(p, 1, n, f) != n) fail(1, "%s: truncated", path.c_str());
  };
  rd(&in.h, sizeof in.h);
  if (std::memcmp(in.h.magic, sysh::kInMagic, 8) != 0 || in.h.version != sysh::kInVersion ||
      in.h.header_bytes != sizeof in.h)
    fail(1, "%s: not a system harness input (version %u)", path.c_str(), sysh::kInVersion);
  for (uint32_t i = 0; i < in.h.n_regions; ++i) {
    sysh::RegionHeader rh{};
    rd(&rh, sizeof rh);
    if (rh.port > sysh::kPortSt) fail(1, "%s: region %u on unknown port %u", path.c_str(), i, rh.port);
    Region r;
    r.port = rh.port;
    r.base = rh.base;
    r.data.resize((rh.bytes + 3u) & ~3u);
    rd(r.data.data(), r.data.size());
    r.data.resize(rh.bytes);
    in.regions.push_back(std::move(r));
  }
  in.writes.resize(in.h.n_writes);
  rd(in.writes.data(), in.writes.size() * sizeof(sysh::RegWrite));
  std::fclose(f);
  return in;
}

const Region& region(const Input& in, uint32_t port) {
  for (const auto& r : in.regions)
    if (r.port == port) return r;
  fail(1, "the input has no region for port %u", port);
}

// The write slave: a byte buffer per target (framebuffer, status buffer).
class WriteMem {
 public:
  struct Buf {
    uint32_t base;
    std::vector<uint8_t> data;
  };
  WriteMem(std::vector<Buf> bufs, uint32_t lat, double stall)
      : bufs_(std::move(bufs)), lat_(lat) {
    stall_.set(stall);
  }
  bool draw_ready(Rng& rng) const { return !stall_.flip(rng); }

  // AW / W handshakes of this clock and the B handshake (bready sampled with the clock low).
  void handshakes(bool aw, uint64_t awaddr, uint32_t awlen, uint32_t awsize, uint32_t awburst,
                  bool awready, bool w, uint64_t wdata, uint32_t wstrb, bool wlast, bool wready,
                  bool bready, uint64_t now) {
    if (aw && awready) {
      if (awburst != 1 || (1u << awsize) > kDataBytes)
        fail(3, "AXI writes: awburst %u, awsize %u at 0x%" PRIx64, awburst, awsize, awaddr);
      const uint64_t bytes = uint64_t{awlen + 1} << awsize;
      if ((awaddr & ~uint64_t{4095}) != ((awaddr + bytes - 1) & ~uint64_t{4095}))
        fail(3, "AXI writes: burst at 0x%" PRIx64 " crosses 4 KiB", awaddr);
      aw_.push_back({awaddr, awlen + 1, awsize, 0});
    }
    if (w && wready) w_.push_back({wdata, wstrb, wlast});
    while (!aw_.empty() && !w_.empty()) {
      Burst& b = aw_.front();
      const Beat d = w_.front();
      w_.pop_front();
      const uint64_t a = (b.addr & ~((uint64_t{1} << b.size) - 1)) + (uint64_t{b.beat} << b.size);
      const uint64_t win = a & ~uint64_t{kDataBytes - 1};
      for (unsigned k = 0; k < kDataBytes; ++k)
        if ((d.strb >> k) & 1) put(win + k, static_cast<uint8_t>(d.data >> (8 * k)));
      ++st.beats;
      if (++b.beat == b.beats) {
        if (!d.last) fail(3, "AXI writes: wlast low on the last beat at 0x%" PRIx64, b.addr);
        b_.push_back(now + lat_);
        aw_.pop_front();
        ++st.bursts;
      } else if (d.last) {
        fail(3, "AXI writes: wlast high before the last beat at 0x%" PRIx64, b.addr);
      }
    }
    if (bvalid_ && bready) {
      bvalid_ = false;
      b_.pop_front();
    }
  }
  // B of this clock.
  bool bvalid(uint64_t now) {
    if (!bvalid_ && !b_.empty() && b_.front() <= now) bvalid_ = true;
    return bvalid_;
  }
  uint64_t outstanding() const { return aw_.size() + b_.size(); }
  // The read port memory whose bytes [lo, hi) this port may write too (the heights region).
  void share(ReadMem* m, uint64_t lo, uint64_t hi) {
    shared_ = m;
    shared_lo_ = lo;
    shared_hi_ = hi;
  }
  const std::vector<Buf>& bufs() const { return bufs_; }
  AxiStats st;

 private:
  struct Burst {
    uint64_t addr;
    uint32_t beats, size, beat;
  };
  struct Beat {
    uint64_t data;
    uint32_t strb;
    bool last;
  };
  void put(uint64_t a, uint8_t v) {
    for (auto& b : bufs_)
      if (a >= b.base && a < b.base + b.data.size()) {
        b.data[a - b.base] = v;
        ++st.bytes;
        return;
      }
    if (shared_ && a >= shared_lo_ && a < shared_hi_ && shared_->poke(a, v)) {
      ++st.bytes;
      return;
    }
    fail(3, "AXI writes: byte at 0x%" PRIx64 " outside the framebuffer, status buffer and heights",
         a);
  }
  std::vector<Buf> bufs_;
  ReadMem* shared_ = nullptr;
  uint64_t shared_lo_ = 0, shared_hi_ = 0;
  uint32_t lat_;
  Coin stall_;
  std::deque<Burst> aw_;
  std::deque<Beat> w_;
  std::deque<uint64_t> b_;
  bool bvalid_ = false;
};

class Sim {
 public:
  Sim(const Input& in, const Options& o)
      : o_(o), rng_(o.seed * 0x9E3779B97F4A7C15ull + 7),
        fmem_("AXI fragments", region(in, sysh::kPortF).data, region(in, sysh::kPortF).base, o.rmem),
        hmem_("AXI heights", region(in, sysh::kPortH).data, region(in, sysh::kPortH).base, o.rmem),
        tmem_("AXI textures", region(in, sysh::kPortT).data, region(in, sysh::kPortT).base, o.rmem),
        wmem_(write_bufs(in), o.w_lat, o.stall) {
    ctx_ = std::make_unique<VerilatedContext>();
    ctx_->randReset(2);
    ctx_->randSeed(static_cast<int>(o.seed & 0x7FFFFFFF));
    top_ = std::make_unique<Vpidm_top>(ctx_.get(), "TOP");
    const Region& h = region(in, sysh::kPortH);
    wmem_.share(&hmem_, h.base, h.base + h.data.size());
  }
  ~Sim() { top_->final(); }
  Sim(const Sim&) = delete;
  Sim& operator=(const Sim&) = delete;

  static std::vector<WriteMem::Buf> write_bufs(const Input& in) {
    std::vector<WriteMem::Buf> b;
    for (const auto& r : in.regions)
      if (r.port == sysh::kPortFb || r.port == sysh::kPortSt) b.push_back({r.base, r.data});
    return b;
  }

  void reset() {
    auto* t = top_.get();
    t->rst_ni = 0;
    lite_idle();
    for (int i = 0; i < 10; ++i) clock();
    t->rst_ni = 1;
    for (int i = 0; i < 4; ++i) clock();
  }

  // One AXI4-Lite write: AW and W offered together until each is taken, then B.
  void write(uint32_t addr, uint32_t value) {
    auto* t = top_.get();
    bool aw = true, w = true;
    for (uint64_t c = 0;; ++c) {
      if (c > 1000) fail(3, "AXI4-Lite write to 0x%03x not answered", addr);
      t->s_axil_awvalid = aw;
      t->s_axil_awaddr = addr;
      t->s_axil_awprot = 0;
      t->s_axil_wvalid = w;
      t->s_axil_wdata = value;
      t->s_axil_wstrb = 0xF;
      t->s_axil_bready = 1;
      const bool done = step([&] {
        if (aw && t->s_axil_awready) aw = false;
        if (w && t->s_axil_wready) w = false;
        if (t->s_axil_bvalid) {
          if (t->s_axil_bresp != 0) fail(3, "AXI4-Lite write to 0x%03x: bresp %u", addr,
                                         static_cast<unsigned>(t->s_axil_bresp));
          return true;
        }
        return false;
      });
      if (done) break;
    }
    lite_idle();
  }

  uint32_t read(uint32_t addr) {
    auto* t = top_.get();
    bool ar = true;
    uint32_t v = 0;
    for (uint64_t c = 0;; ++c) {
      if (c > 1000) fail(3, "AXI4-Lite read of 0x%03x not answered", addr);
      t->s_axil_arvalid = ar;
      t->s_axil_araddr = addr;
      t->s_axil_arprot = 0;
      t->s_axil_rready = 1;
      const bool done = step([&] {
        if (ar && t->s_axil_arready) ar = false;
        if (t->s_axil_rvalid) {
          v = t->s_axil_rdata;
          return true;
        }
        return false;
      });
      if (done) break;
    }
    lite_idle();
    return v;
  }

  uint64_t read48(uint32_t lo) { return read(lo) | (uint64_t{read(lo + 4)} << 32); }

  // Clocks until irq_o (fail after `limit`).
  uint64_t wait_irq(uint64_t limit) {
    const uint64_t t0 = now_;
    while (!top_->irq_o) {
      if (now_ - t0 >= limit)
        fail(2, "no interrupt %" PRIu64 " clocks after CTRL.start (bursts pending: F %" PRIu64
                ", H %" PRIu64 ", T %" PRIu64 ", writes %" PRIu64 ")", limit, fmem_.pending(),
             hmem_.pending(), tmem_.pending(), wmem_.outstanding());
      clock();
    }
    return now_ - t0;
  }

  uint64_t now() const { return now_; }
  const ReadMem& fmem() const { return fmem_; }
  const ReadMem& hmem() const { return hmem_; }
  const ReadMem& tmem() const { return tmem_; }
  const WriteMem& wmem() const { return wmem_; }

 private:
  void lite_idle() {
    auto* t = top_.get();
    t->s_axil_awvalid = 0;
    t->s_axil_wvalid = 0;
    t->s_axil_bready = 0;
    t->s_axil_arvalid = 0;
    t->s_axil_rready = 0;
  }

  // One clock: memories drive, eval, `sample` sees the handshakes, memories take theirs, edge.
  template <typename F>
  bool step(F sample) {
    auto* t = top_.get();
    t->clk_i = 0;
    t->m_axi_f_arready = fmem_.draw_arready(rng_);
    t->m_axi_h_arready = hmem_.draw_arready(rng_);
    t->m_axi_t_arready = tmem_.draw_arready(rng_);
    t->m_axi_w_awready = wmem_.draw_ready(rng_);
    t->m_axi_w_wready = wmem_.draw_ready(rng_);
    harness::drive_r<kDataBytes>(fmem_.drive(now_, rng_), t->m_axi_f_rid, t->m_axi_f_rdata,
                                 t->m_axi_f_rresp, t->m_axi_f_rlast, t->m_axi_f_rvalid);
    harness::drive_r<kDataBytes>(hmem_.drive(now_, rng_), t->m_axi_h_rid, t->m_axi_h_rdata,
                                 t->m_axi_h_rresp, t->m_axi_h_rlast, t->m_axi_h_rvalid);
    harness::drive_r<kDataBytes>(tmem_.drive(now_, rng_), t->m_axi_t_rid, t->m_axi_t_rdata,
                                 t->m_axi_t_rresp, t->m_axi_t_rlast, t->m_axi_t_rvalid);
    t->m_axi_w_bvalid = wmem_.bvalid(now_);
    t->m_axi_w_bid = 0;
    t->m_axi_w_bresp = 0;
    t->eval();
    const bool r = sample();
    if (!t->rst_ni) {  // registers hold their random initial values until the first reset edge
      t->clk_i = 1;
      t->eval();
      ++now_;
      return r;
    }
    fmem_.handshakes(harness::ArSignals{static_cast<bool>(t->m_axi_f_arvalid), t->m_axi_f_arid,
                                        t->m_axi_f_araddr, t->m_axi_f_arlen, t->m_axi_f_arsize,
                                        t->m_axi_f_arburst},
                     t->m_axi_f_arready, t->m_axi_f_rready, now_, rng_);
    hmem_.handshakes(harness::ArSignals{static_cast<bool>(t->m_axi_h_arvalid), t->m_axi_h_arid,
                                        t->m_axi_h_araddr, t->m_axi_h_arlen, t->m_axi_h_arsize,
                                        t->m_axi_h_arburst},
                     t->m_axi_h_arready, t->m_axi_h_rready, now_, rng_);
    tmem_.handshakes(harness::ArSignals{static_cast<bool>(t->m_axi_t_arvalid), t->m_axi_t_arid,
                                        t->m_axi_t_araddr, t->m_axi_t_arlen, t->m_axi_t_arsize,
                                        t->m_axi_t_arburst},
                     t->m_axi_t_arready, t->m_axi_t_rready, now_, rng_);
    wmem_.handshakes(t->m_axi_w_awvalid, t->m_axi_w_awaddr, t->m_axi_w_awlen, t->m_axi_w_awsize,
                     t->m_axi_w_awburst, t->m_axi_w_awready, t->m_axi_w_wvalid, t->m_axi_w_wdata,
                     t->m_axi_w_wstrb, t->m_axi_w_wlast, t->m_axi_w_wready, t->m_axi_w_bready,
                     now_);
    t->clk_i = 1;
    t->eval();
    ++now_;
    return r;
  }

  void clock() { step([] { return false; }); }

  const Options& o_;
  Rng rng_;
  ReadMem fmem_, hmem_, tmem_;
  WriteMem wmem_;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vpidm_top> top_;
  uint64_t now_ = 0;
};

#define REG(r) static_cast<uint32_t>(offsetof(pidm_regs_t, r))

void write_output(const std::string& path, const WriteMem& w, const ReadMem& hmem,
                  const Input& in, uint32_t pyr_cycles) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) fail(1, "cannot write %s: %s", path.c_str(), std::strerror(errno));
  const std::vector<uint8_t>* fb = nullptr;
  const std::vector<uint8_t>* st = nullptr;
  for (const auto& b : w.bufs()) {
    if (b.base == in.h.fb_base && b.data.size() == in.h.fb_bytes) fb = &b.data;
    else if (b.base == in.h.st_base && b.data.size() == in.h.st_bytes) st = &b.data;
  }
  if (!fb) fail(1, "the input has no framebuffer region at 0x%08x", in.h.fb_base);
  static const std::vector<uint8_t> none;
  if (!st) st = &none;
  const Region& hr = region(in, sysh::kPortH);
  std::vector<uint8_t> heights(hr.data.size());
  for (size_t i = 0; i < heights.size(); ++i) heights[i] = hmem.peek(hr.base + i);
  uint32_t head[8] = {};
  std::memcpy(head, sysh::kOutMagic, 8);
  head[2] = static_cast<uint32_t>(fb->size());
  head[3] = static_cast<uint32_t>(st->size());
  head[4] = static_cast<uint32_t>(heights.size());
  head[5] = pyr_cycles;
  bool ok = std::fwrite(head, sizeof head, 1, f) == 1;
  const uint8_t pad[4] = {};
  for (const auto* b : {fb, st, static_cast<const std::vector<uint8_t>*>(&heights)}) {
    if (!b->empty()) ok = ok && std::fwrite(b->data(), 1, b->size(), f) == b->size();
    const size_t p = (4 - b->size() % 4) % 4;
    if (p) ok = ok && std::fwrite(pad, 1, p, f) == p;
  }
  if (std::fclose(f) != 0 || !ok) fail(1, "cannot write %s", path.c_str());
}

double ratio(uint64_t a, uint64_t b) {
  return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  harness::set_name("system_harness");
  const Options o = parse_args(argc, argv);
  const Input in = read_input(o.in);
  const uint32_t n = in.h.n_frags;
  if (in.writes.empty()) fail(1, "no register writes (the last one starts the frame)");
  const size_t n_pyr = in.h.n_pyr;
  if (n_pyr >= in.writes.size()) fail(1, "%zu pyramid writes of %zu: no frame", n_pyr,
                                      in.writes.size());

  const auto t0 = std::chrono::steady_clock::now();
  Sim sim(in, o);
  sim.reset();
  if (sim.read(REG(ID)) != PIDM_REGS__ID__ID_reset) fail(3, "ID register: not a pidm_top");
  uint64_t pyr_cycles = 0;
  if (n_pyr) {   // the pyramid build: its writes, the last one CTRL.pyr_start, its interrupt
    for (size_t i = 0; i + 1 < n_pyr; ++i) sim.write(in.writes[i].addr, in.writes[i].value);
    const uint64_t t = sim.now();
    sim.write(in.writes[n_pyr - 1].addr, in.writes[n_pyr - 1].value);
    sim.wait_irq(o.timeout ? o.timeout : 4000000ull);
    pyr_cycles = sim.now() - t;
    const uint32_t pi = sim.read(REG(INTR_STATE));
    const uint32_t pe = sim.read(REG(ERROR));
    if (pi != PIDM_REGS__INTR_STATE__PYR_DONE_bm || pe != 0)
      fail(3, "pyramid build ended with INTR_STATE 0x%x, ERROR 0x%x", pi, pe);
    sim.write(REG(INTR_STATE), pi);
  }
  for (size_t i = n_pyr; i + 1 < in.writes.size(); ++i) sim.write(in.writes[i].addr, in.writes[i].value);
  const uint64_t start = sim.now();
  sim.write(in.writes.back().addr, in.writes.back().value);
  const uint64_t timeout = o.timeout ? o.timeout : 2000000ull + 4000ull * n;
  sim.wait_irq(timeout);
  const uint64_t cycles = sim.now() - start;
  const uint32_t intr = sim.read(REG(INTR_STATE));
  const uint32_t err = sim.read(REG(ERROR));
  const uint32_t progress = sim.read(REG(PROGRESS));
  sim.write(REG(INTR_STATE), intr);
  struct Stat {
    const char* name;
    uint32_t off;
  };
  const Stat stats[] = {
      {"cycles", REG(STATS.cycles)}, {"pixels", REG(STATS.pixels)}, {"iters", REG(STATS.iters)},
      {"h_hits", REG(STATS.h_hits)}, {"h_misses", REG(STATS.h_misses)},
      {"h_bytes", REG(STATS.h_bytes)}, {"t_requests", REG(STATS.t_requests)},
      {"t_quad_hits", REG(STATS.t_quad_hits)}, {"t_line_misses", REG(STATS.t_line_misses)},
      {"t_texel_hits", REG(STATS.t_texel_hits)}, {"t_bytes", REG(STATS.t_bytes)}};
  uint64_t v[11];
  for (size_t i = 0; i < 11; ++i) v[i] = sim.read48(stats[i].off);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (intr != PIDM_REGS__INTR_STATE__FRAME_DONE_bm || err != 0)
    fail(3, "frame ended with INTR_STATE 0x%x, ERROR 0x%x", intr, err);
  if (progress != n || v[1] != n)
    fail(3, "PROGRESS %u, STATS.pixels %" PRIu64 " for %u fragments", progress, v[1], n);
  write_output(o.out, sim.wmem(), sim.hmem(), in, static_cast<uint32_t>(pyr_cycles));

  const uint64_t h_hits = v[3], h_misses = v[4], t_req = v[6], t_qh = v[7], t_th = v[9];
  const double cps = wall > 0 ? static_cast<double>(sim.now()) / wall : 0.0;
  if (!o.stats.empty()) {
    FILE* f = std::fopen(o.stats.c_str(), "w");
    if (!f) fail(1, "cannot write %s: %s", o.stats.c_str(), std::strerror(errno));
    std::fprintf(f, "{\n  \"pixels\": %u,\n  \"cycles\": %" PRIu64 ",\n", n, cycles);
    std::fprintf(f, "  \"pyramid_cycles\": %" PRIu64 ",\n", pyr_cycles);
    std::fprintf(f, "  \"busy_cycles\": %" PRIu64 ",\n  \"iterations\": %" PRIu64 ",\n", v[0],
                 v[2]);
    std::fprintf(f, "  \"height_cache_hits\": %" PRIu64 ",\n  \"height_cache_misses\": %" PRIu64
                    ",\n", h_hits, h_misses);
    std::fprintf(f, "  \"height_cache_hit_rate\": %.6f,\n", ratio(h_hits, h_hits + h_misses));
    std::fprintf(f, "  \"height_mem_bytes\": %" PRIu64 ",\n", v[5]);
    std::fprintf(f, "  \"texture_requests\": %" PRIu64 ",\n  \"texture_quad_hits\": %" PRIu64
                    ",\n  \"texture_texel_hits\": %" PRIu64 ",\n", t_req, t_qh, t_th);
    std::fprintf(f, "  \"texture_cache_hit_rate\": %.6f,\n", ratio(t_th, 4 * t_req));
    std::fprintf(f, "  \"texture_quad_hit_rate\": %.6f,\n", ratio(t_qh, t_req));
    std::fprintf(f, "  \"texture_line_misses\": %" PRIu64 ",\n", v[8]);
    std::fprintf(f, "  \"texture_mem_bytes\": %" PRIu64 ",\n  \"mem_bytes\": %" PRIu64 ",\n",
                 v[10], v[5] + v[10]);
    std::fprintf(f, "  \"fragment_mem_bytes\": %" PRIu64 ",\n", sim.fmem().st.bytes);
    std::fprintf(f, "  \"framebuffer_bytes_written\": %" PRIu64 ",\n", sim.wmem().st.bytes);
    std::fprintf(f, "  \"axi_h_bytes\": %" PRIu64 ",\n  \"axi_t_bytes\": %" PRIu64 ",\n",
                 sim.hmem().st.bytes, sim.tmem().st.bytes);
    std::fprintf(f, "  \"read_latency_min\": %u,\n  \"read_latency_max\": %u,\n",
                 o.rmem.lat_min, o.rmem.lat_max);
    std::fprintf(f, "  \"cycles_per_pixel\": %.6f,\n  \"seed\": %" PRIu64 ",\n",
                 ratio(cycles, n), o.seed);
    std::fprintf(f, "  \"sim_clocks\": %" PRIu64 ",\n  \"wall_seconds\": %.6f,\n", sim.now(),
                 wall);
    std::fprintf(f, "  \"clocks_per_second\": %.1f\n}\n", cps);
    if (std::fclose(f) != 0) fail(1, "cannot write %s", o.stats.c_str());
  }
  if (!o.quiet)
    std::printf("system_harness: %u pixels, %" PRIu64 " clocks from CTRL.start to the interrupt "
                "(%.3f / pixel), %" PRIu64 " iterations; %" PRIu64 " clocks in %.3f s\n",
                n, cycles, ratio(cycles, n), v[2], sim.now(), wall);
  return 0;
}
