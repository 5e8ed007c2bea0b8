// SPDX-License-Identifier: Apache-2.0
// traverse_harness: a Verilator main that runs traverse_system (rtl/traverse/traverse_system.sv) on
// a whole ray batch, fast.  tb/harness/traverse_system.py builds it (build/harness/<variant>/) and drives it.
//
//   input file  -> configuration, memory image (served over AXI at cfg_base), rays
//   ray stream  -> traverse_system -> result stream -> output file (in input order) + JSON stats
//
// File formats: traverse_harness.h.  Command line: --help.
//
// What it checks, failing loudly (message on stderr, non-zero exit status):
//   - every ray comes back exactly once (no unknown, duplicate or missing id), before --timeout
//     clocks (exit 2 on timeout, 3 on any other check), and then nothing more comes out for 40
//     clocks and idle_o is 1;
//   - the AXI read master keeps the protocol: AR payload stable while arvalid waits for arready,
//     arburst not reserved, arsize within the bus, INCR bursts inside a 4 KiB page, WRAP bursts of
//     2, 4, 8 or 16 beats;
//   - with --warm, that the measured run returns exactly what the warm-up run returned.
//
// Clocking: per clock, inputs are set with clk low and evaluated, the handshakes are sampled
// (valid && ready), then the rising edge is evaluated.  Ray ids on the ray stream are the ray's
// index modulo 2^RAY_ID_W; a ray whose id is still in flight waits (the stream stalls) so ids stay
// unique among the rays in the unit.
//
// Memory model (AXI4 slave, read channels; axi_mem.h, shared with pipeline_harness.cpp): an
// address accepted in clock c presents its first beat in clock c + L (L fixed or drawn uniformly
// in [min, max] per burst, L >= 1); bursts of one ID come back in order, bursts of different IDs
// in the order they become ready (never interleaved beat by beat); one beat per clock unless
// --rvalid-gap inserts bubbles; a presented beat is held until rready.  The memory holds the image
// at cfg_base and zeros around it up to the 4 KiB pages the image touches (so line reads of an
// unaligned image stay inside); beat data is the bus-aligned DATA_W/8-byte window; a transfer
// reaching outside the memory answers DECERR, one overlapping an --err range answers SLVERR.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "Vtraverse_system.h"
#include "axi_mem.h"
#include "harness_common.h"
#include "traverse_harness.h"
#include "verilated.h"
#ifdef HARNESS_TRACE
#include "verilated_fst_c.h"
#endif

// Parameters the model was built with (tb/harness/traverse_system.py passes them as -G and -D alike).
#ifndef HARNESS_AXI_DATA_W
#define HARNESS_AXI_DATA_W 64
#endif
#ifndef HARNESS_AXI_ID_W
#define HARNESS_AXI_ID_W 4
#endif
#ifndef HARNESS_RAY_ID_W
#define HARNESS_RAY_ID_W 16
#endif

namespace {

using harness::AxiMemConfig;
using harness::AxiStats;
using harness::Coin;
using harness::fail;
using harness::parse_prob;
using harness::parse_u64;
using harness::Rng;

constexpr unsigned kDataBytes = HARNESS_AXI_DATA_W / 8;
constexpr unsigned kAxiIds = 1u << HARNESS_AXI_ID_W;
constexpr uint32_t kRayTags = 1u << HARNESS_RAY_ID_W;
static_assert(HARNESS_AXI_DATA_W >= 8 && (HARNESS_AXI_DATA_W & (HARNESS_AXI_DATA_W - 1)) == 0,
              "AXI data width is a power of two");
static_assert(HARNESS_RAY_ID_W >= 1 && HARNESS_RAY_ID_W <= 24, "ray id width 1 .. 24");
static_assert(HARNESS_AXI_ID_W >= 1 && HARNESS_AXI_ID_W <= 8, "AXI id width 1 .. 8");

const char* kUsage = R"(usage: traverse_harness --in FILE --out FILE [options]

Runs traverse_system (traverse_unit + height_cache, AXI4 memory model) on a ray batch.

  --in FILE           input: configuration, memory image, rays (tb/harness/traverse_harness.h)
  --out FILE          output: one record per ray, in input order
  --stats FILE        JSON statistics (cycles, rays, iterations, cache hits / misses, bytes, ...)
  --latency L         AXI read latency: first beat L clocks after the address (default 20)
  --latency MIN:MAX   ... drawn uniformly per burst in [MIN, MAX] (MIN >= 1)
  --seed S            seed of every random choice below and of the model's X values (default 0)
  --ray-gap P         probability that the ray stream offers nothing in a clock (default 0)
  --res-stall P       probability that res_ready is low in a clock (default 0)
  --ar-stall P        probability that arready is low in a clock (default 0)
  --rvalid-gap P      probability of a bubble before a read beat (default 0)
  --err LO:HI         byte addresses [LO, HI) (decimal or 0x hex) answer SLVERR; repeatable
  --timeout N         fail (exit 2) when a run takes more than N clocks
                      (default 2000000 + 4000 per ray)
  --warm              run the batch twice: a warm-up run (its results must equal the measured
                      run's), clear the statistics, then the measured run (warm cache)
  --waves FILE.fst    write an FST waveform (only the waves variant of the binary has tracing)
  --quiet             no summary line on stdout
  --help              this text

Exit status: 0 all rays back exactly once; 1 usage or file error; 2 timeout; 3 a failed check
(unknown / duplicate / missing ray id, AXI protocol violation, warm / measured runs differ).
)";

using Memory = harness::AxiReadSlave<kDataBytes, kAxiIds>;

struct Options {
  std::string in, out, stats, waves;
  AxiMemConfig mem;  // latency, rvalid gaps, arready stalls, SLVERR ranges
  uint64_t seed = 0;
  double ray_gap = 0, res_stall = 0;
  uint64_t timeout = 0;
  bool warm = false, quiet = false;
};

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto val = [&](const char* name) -> std::string {
      if (i + 1 >= argc) fail(1, "%s needs a value (see --help)", name);
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a == "--in") {
      o.in = val("--in");
    } else if (a == "--out") {
      o.out = val("--out");
    } else if (a == "--stats") {
      o.stats = val("--stats");
    } else if (a == "--waves") {
      o.waves = val("--waves");
    } else if (a == "--latency") {
      std::tie(o.mem.lat_min, o.mem.lat_max) =
          harness::parse_latency(val("--latency"), "--latency");
    } else if (a == "--seed") {
      o.seed = parse_u64(val("--seed"), "seed");
    } else if (a == "--ray-gap") {
      o.ray_gap = parse_prob(val("--ray-gap"), "--ray-gap");
    } else if (a == "--res-stall") {
      o.res_stall = parse_prob(val("--res-stall"), "--res-stall");
    } else if (a == "--ar-stall") {
      o.mem.ar_stall = parse_prob(val("--ar-stall"), "--ar-stall");
    } else if (a == "--rvalid-gap") {
      o.mem.rvalid_gap = parse_prob(val("--rvalid-gap"), "--rvalid-gap");
    } else if (a == "--err") {
      o.mem.err.push_back(harness::parse_range(val("--err"), "--err"));
    } else if (a == "--timeout") {
      o.timeout = parse_u64(val("--timeout"), "timeout");
    } else if (a == "--warm") {
      o.warm = true;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      fail(1, "unknown argument '%s' (see --help)", a.c_str());
    }
  }
  if (o.in.empty() || o.out.empty()) fail(1, "--in and --out are required (see --help)");
#ifndef HARNESS_TRACE
  if (!o.waves.empty())
    fail(1, "--waves: this binary is built without tracing; use the 'waves' variant "
            "(tb/harness/traverse_system.py builds it for trace_rtl(..., waves=FILE))");
#endif
  return o;
}

struct Input {
  trvh::InHeader h;
  std::vector<uint8_t> mem;
  std::vector<trvh::Ray> rays;
};

Input read_input(const std::string& path) {
  Input in;
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) fail(1, "cannot open input %s: %s", path.c_str(), std::strerror(errno));
  if (std::fread(&in.h, sizeof in.h, 1, f) != 1) fail(1, "%s: short header", path.c_str());
  if (std::memcmp(in.h.magic, trvh::kInMagic, 8) != 0) fail(1, "%s: not a harness input file", path.c_str());
  if (in.h.version != trvh::kInVersion || in.h.header_bytes != sizeof(trvh::InHeader))
    fail(1, "%s: version %u / header %u bytes, this harness reads version %u / %zu bytes",
         path.c_str(), in.h.version, in.h.header_bytes, trvh::kInVersion, sizeof(trvh::InHeader));
  in.mem.resize((static_cast<size_t>(in.h.mem_bytes) + 3) & ~size_t{3});
  if (!in.mem.empty() && std::fread(in.mem.data(), in.mem.size(), 1, f) != 1)
    fail(1, "%s: short memory image", path.c_str());
  in.mem.resize(in.h.mem_bytes);
  in.rays.resize(in.h.n_rays);
  if (in.h.n_rays && std::fread(in.rays.data(), sizeof(trvh::Ray), in.h.n_rays, f) != in.h.n_rays)
    fail(1, "%s: short ray list (%u rays announced)", path.c_str(), in.h.n_rays);
  char extra;
  if (std::fread(&extra, 1, 1, f) != 0) fail(1, "%s: trailing bytes after the rays", path.c_str());
  std::fclose(f);
  return in;
}

// Set a Verilator port of any width from a little-endian byte window.
struct UnitStats {
  uint64_t cycles, rays_in, rays_out, iters, lookups, crossings, level_ups, descents;
  uint64_t c_hits, c_misses, c_bytes, c_lines;
};

template <typename Top>
UnitStats snapshot(const Top* t) {
  return UnitStats{t->stat_cycles_o,    t->stat_rays_in_o,     t->stat_rays_out_o,
                   t->stat_iters_o,     t->stat_lookups_o,     t->stat_crossings_o,
                   t->stat_level_ups_o, t->stat_descents_o,    t->stat_cache_hits_o,
                   t->stat_cache_misses_o, t->stat_mem_bytes_o, t->stat_mem_lines_o};
}

class Sim {
 public:
  Sim(const Input& in, const Options& o)
      : in_(in), o_(o), rng_(o.seed * 0x9E3779B97F4A7C15ull + 1),
        mem_("AXI", in.mem, in.h.base, o.mem) {
    ctx_ = std::make_unique<VerilatedContext>();
    ctx_->randReset(2);
    ctx_->randSeed(static_cast<int>(o.seed & 0x7FFFFFFF));
#ifdef HARNESS_TRACE
    if (!o.waves.empty()) ctx_->traceEverOn(true);
#endif
    top_ = std::make_unique<Vtraverse_system>(ctx_.get(), "TOP");
#ifdef HARNESS_TRACE
    if (!o.waves.empty()) {
      fst_ = std::make_unique<VerilatedFstC>();
      top_->trace(fst_.get(), 99);
      fst_->open(o.waves.c_str());
    }
#endif
    ray_gap_.set(o.ray_gap);
    res_stall_.set(o.res_stall);
    tag_index_.assign(kRayTags, 0);
    tag_busy_.assign(kRayTags, 0);
  }

  ~Sim() {
#ifdef HARNESS_TRACE
    if (fst_) fst_->close();
#endif
    top_->final();
  }

  void configure_and_reset() {
    auto* t = top_.get();
    const auto& h = in_.h;
    t->cfg_method_i = h.method;
    t->cfg_width_i = h.width;
    t->cfg_height_i = h.height;
    t->cfg_root_level_i = h.root_level;
    t->cfg_bits16_i = h.bits16;
    t->cfg_base_i = h.base;
    t->cfg_root_code_i = h.root_code;
    t->cfg_iter_cap_i = h.iter_cap;
    t->ray_valid_i = 0;
    t->res_ready_i = 0;
    t->m_axi_arready = 0;
    t->m_axi_rvalid = 0;
    t->clr_stats_i = 0;
    t->rst_ni = 0;
    // The level-offset table is written during the reset (its write port does not look at
    // rst_ni), so the unit starts as many clocks after the reset as before the table existed.
    for (unsigned i = 0; i < std::max(10u, trvh::kMaxLevels); ++i) {
      t->hlt_we_i = i < trvh::kMaxLevels;
      t->hlt_waddr_i = i % trvh::kMaxLevels;
      t->hlt_wdata_i = h.level_off[i % trvh::kMaxLevels];
      clock();
    }
    t->hlt_we_i = 0;
    t->rst_ni = 1;
    for (int i = 0; i < 8; ++i) clock();  // the configuration settles (>= 5 clocks)
  }

  void pulse_clear_stats() {
    top_->clr_stats_i = 1;
    clock();
    top_->clr_stats_i = 0;
  }

  // One run of the whole batch; results land in `out` (input order).  Returns the clocks used.
  uint64_t run(std::vector<trvh::OutRecord>& out, const char* what) {
    auto* t = top_.get();
    const uint32_t n = in_.h.n_rays;
    out.assign(n, trvh::OutRecord{});
    std::vector<uint8_t> seen(n, 0);
    const uint64_t timeout = o_.timeout ? o_.timeout : 2000000ull + 4000ull * n;
    uint32_t next = 0, done = 0;
    bool presenting = false;
    uint32_t cur_tag = 0;
    const uint64_t start = now_;
    uint64_t last = now_;
    while (done < n) {
      if (now_ - start >= timeout) timeout_report(what, n, next, done, timeout);
      // ---- inputs of this clock (clk low) ----
      t->clk_i = 0;
      if (!presenting && next < n && !ray_gap_.flip(rng_)) {
        cur_tag = next & (kRayTags - 1);
        if (!tag_busy_[cur_tag]) {
          const trvh::Ray& r = in_.rays[next];
          t->ray_id_i = cur_tag;
          t->ray_u0_i = r.u0 & 0xFFFFFF;
          t->ray_v0_i = r.v0 & 0xFFFFFF;
          t->ray_du_i = r.du & 0xFFFFFF;
          t->ray_dv_i = r.dv & 0xFFFFFF;
          presenting = true;
        } else {
          ++tag_stalls_;
        }
      }
      t->ray_valid_i = presenting;
      t->res_ready_i = !res_stall_.flip(rng_);
      t->m_axi_arready = mem_.draw_arready(rng_);
      drive_r(t);
      t->eval();
      dump(2 * now_);
      // ---- handshakes of this clock ----
      if (presenting && t->ray_ready_o) {
        tag_busy_[cur_tag] = 1;
        tag_index_[cur_tag] = next;
        ++next;
        presenting = false;
      }
      if (t->res_valid_o && t->res_ready_i) {
        const uint32_t tag = t->res_id_o;
        if (!tag_busy_[tag])
          fail(3, "%s run, clock %" PRIu64 ": result with ray id %u, which is not in flight "
                  "(a duplicate or an id never sent)", what, now_, tag);
        const uint32_t idx = tag_index_[tag];
        if (seen[idx]) fail(3, "%s run: ray %u returned twice", what, idx);
        seen[idx] = 1;
        tag_busy_[tag] = 0;
        trvh::OutRecord& rec = out[idx];
        rec.id = idx;
        rec.t = t->res_t_o;
        rec.u = t->res_u_o;
        rec.v = t->res_v_o;
        rec.flags = (t->res_hit_o ? uint32_t{trvh::kFlagHit} : 0u) |
                    (t->res_invalid_o ? uint32_t{trvh::kFlagInvalid} : 0u) |
                    (t->res_capped_o ? uint32_t{trvh::kFlagCapped} : 0u) |
                    (t->res_err_o ? uint32_t{trvh::kFlagErr} : 0u);
        rec.iterations = t->res_iters_o;
        ++done;
        last = now_;
      }
      axi_handshakes(t);
      // ---- rising edge ----
      t->clk_i = 1;
      t->eval();
      dump(2 * now_ + 1);
      ++now_;
    }
    for (uint32_t i = 0; i < n; ++i)
      if (!seen[i]) fail(3, "%s run: ray %u never came back", what, i);
    // Nothing more may come out: two passes of the loop with res_ready high, then idle_o.
    t->ray_valid_i = 0;
    for (int i = 0; i < 40; ++i) {
      t->clk_i = 0;
      t->res_ready_i = 1;
      drive_r(t);
      t->eval();
      dump(2 * now_);
      if (t->res_valid_o)
        fail(3, "%s run: an extra result (ray id %u) after every ray came back", what,
             static_cast<unsigned>(t->res_id_o));
      axi_handshakes(t);
      t->clk_i = 1;
      t->eval();
      dump(2 * now_ + 1);
      ++now_;
    }
    if (!t->idle_o) fail(3, "%s run: idle_o is 0 after every ray came back", what);
    t->res_ready_i = 0;
    return n ? last - start + 1 : 0;
  }

  uint64_t now() const { return now_; }
  uint64_t tag_stalls() const { return tag_stalls_; }
  Memory& mem() { return mem_; }
  const Vtraverse_system* top() const { return top_.get(); }

 private:
  void dump(uint64_t ts) {
#ifdef HARNESS_TRACE
    if (fst_) fst_->dump(ts);
#else
    (void)ts;
#endif
  }

  // The memory's R channel of this clock (clk low, before eval).
  void drive_r(Vtraverse_system* t) {
    harness::drive_r<kDataBytes>(mem_.drive(now_, rng_), t->m_axi_rid, t->m_axi_rdata,
                                 t->m_axi_rresp, t->m_axi_rlast, t->m_axi_rvalid);
  }

  // Address and data channel handshakes (sampled with clk low, after eval).
  void axi_handshakes(Vtraverse_system* t) {
    mem_.handshakes(harness::ArSignals{static_cast<bool>(t->m_axi_arvalid), t->m_axi_arid,
                                       t->m_axi_araddr, t->m_axi_arlen, t->m_axi_arsize,
                                       t->m_axi_arburst},
                    t->m_axi_arready, t->m_axi_rready, now_, rng_);
  }

  void clock() {
    top_->clk_i = 0;
    top_->ray_valid_i = 0;
    drive_r(top_.get());
    top_->eval();
    dump(2 * now_);
    axi_handshakes(top_.get());
    top_->clk_i = 1;
    top_->eval();
    dump(2 * now_ + 1);
    ++now_;
  }

  [[noreturn]] void timeout_report(const char* what, uint32_t n, uint32_t next, uint32_t done,
                                   uint64_t timeout) {
    std::fprintf(stderr,
                 "traverse_harness: %s run: %u of %u rays back after %" PRIu64
                 " clocks (%u sent, idle_o=%d, AXI bursts pending %" PRIu64 ")\n",
                 what, done, n, timeout, next, static_cast<int>(top_->idle_o), mem_.pending());
    unsigned shown = 0;
    for (uint32_t tag = 0; tag < kRayTags && shown < 10; ++tag)
      if (tag_busy_[tag]) {
        std::fprintf(stderr, "  still in flight: ray %u (id %u)\n", tag_index_[tag], tag);
        ++shown;
      }
#ifdef HARNESS_TRACE
    if (fst_) fst_->close();
    fst_.reset();
#endif
    fail(2, "timeout after %" PRIu64 " clocks (--timeout)", timeout);
  }

  const Input& in_;
  const Options& o_;
  Rng rng_;
  Memory mem_;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vtraverse_system> top_;
#ifdef HARNESS_TRACE
  std::unique_ptr<VerilatedFstC> fst_;
#endif
  Coin ray_gap_, res_stall_;
  std::vector<uint32_t> tag_index_;
  std::vector<uint8_t> tag_busy_;
  uint64_t now_ = 0, tag_stalls_ = 0;
};

void write_output(const std::string& path, const std::vector<trvh::OutRecord>& out) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) fail(1, "cannot write %s: %s", path.c_str(), std::strerror(errno));
  trvh::OutHeader h{};
  std::memcpy(h.magic, trvh::kOutMagic, 8);
  h.n_rays = static_cast<uint32_t>(out.size());
  h.record_bytes = sizeof(trvh::OutRecord);
  bool ok = std::fwrite(&h, sizeof h, 1, f) == 1;
  if (!out.empty()) ok = ok && std::fwrite(out.data(), sizeof(trvh::OutRecord), out.size(), f) == out.size();
  if (std::fclose(f) != 0 || !ok) fail(1, "cannot write %s", path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  harness::set_name("traverse_harness");
  const Options o = parse_args(argc, argv);
  const Input in = read_input(o.in);
  const uint32_t n = in.h.n_rays;

  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();  // this process's CPU time (the machine may be busy)
  std::vector<trvh::OutRecord> out, warm_out;
  uint64_t cycles = 0;
  UnitStats before{}, after{};
  AxiStats axi_before{};
  uint64_t clocks = 0;
  {
    Sim sim(in, o);
    sim.configure_and_reset();
    if (o.warm) {
      sim.run(warm_out, "warm-up");
      sim.pulse_clear_stats();
    }
    before = snapshot(sim.top());
    axi_before = sim.mem().st;
    cycles = sim.run(out, o.warm ? "measured" : "the");
    after = snapshot(sim.top());
    if (o.warm) {
      for (uint32_t i = 0; i < n; ++i)
        if (std::memcmp(&out[i], &warm_out[i], sizeof(trvh::OutRecord)) != 0)
          fail(3, "ray %u: the measured run differs from the warm-up run", i);
    }
    clocks = sim.now();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;

    write_output(o.out, out);

    uint64_t iters = 0, hits = 0, invalid = 0, capped = 0, err = 0;
    for (const auto& r : out) {
      iters += r.iterations;
      hits += (r.flags & trvh::kFlagHit) != 0;
      invalid += (r.flags & trvh::kFlagInvalid) != 0;
      capped += (r.flags & trvh::kFlagCapped) != 0;
      err += (r.flags & trvh::kFlagErr) != 0;
    }
    const AxiStats& ax = sim.mem().st;
    auto d = [&](uint64_t UnitStats::*f) { return after.*f - before.*f; };
    const uint64_t c_hits = d(&UnitStats::c_hits), c_misses = d(&UnitStats::c_misses);
    const double cps = wall > 0 ? static_cast<double>(clocks) / wall : 0.0;
    const double cps_cpu = cpu > 0 ? static_cast<double>(clocks) / cpu : 0.0;
    if (!o.stats.empty()) {
      FILE* f = std::fopen(o.stats.c_str(), "w");
      if (!f) fail(1, "cannot write %s: %s", o.stats.c_str(), std::strerror(errno));
      std::fprintf(f, "{\n");
      std::fprintf(f, "  \"rays\": %u,\n", n);
      std::fprintf(f, "  \"cycles\": %" PRIu64 ",\n", cycles);
      std::fprintf(f, "  \"busy_cycles\": %" PRIu64 ",\n", d(&UnitStats::cycles));
      std::fprintf(f, "  \"iterations\": %" PRIu64 ",\n", iters);
      std::fprintf(f, "  \"stat_iterations\": %" PRIu64 ",\n", d(&UnitStats::iters));
      std::fprintf(f, "  \"lookups\": %" PRIu64 ",\n", d(&UnitStats::lookups));
      std::fprintf(f, "  \"crossings\": %" PRIu64 ",\n", d(&UnitStats::crossings));
      std::fprintf(f, "  \"descents\": %" PRIu64 ",\n", d(&UnitStats::descents));
      std::fprintf(f, "  \"level_ups\": %" PRIu64 ",\n", d(&UnitStats::level_ups));
      std::fprintf(f, "  \"rays_in\": %" PRIu64 ",\n", d(&UnitStats::rays_in));
      std::fprintf(f, "  \"rays_out\": %" PRIu64 ",\n", d(&UnitStats::rays_out));
      std::fprintf(f, "  \"hits\": %" PRIu64 ",\n", hits);
      std::fprintf(f, "  \"invalid\": %" PRIu64 ",\n", invalid);
      std::fprintf(f, "  \"capped\": %" PRIu64 ",\n", capped);
      std::fprintf(f, "  \"errors\": %" PRIu64 ",\n", err);
      std::fprintf(f, "  \"height_cache_hits\": %" PRIu64 ",\n", c_hits);
      std::fprintf(f, "  \"height_cache_misses\": %" PRIu64 ",\n", c_misses);
      std::fprintf(f, "  \"height_cache_hit_rate\": %.6f,\n",
                   c_hits + c_misses ? static_cast<double>(c_hits) / (c_hits + c_misses) : 0.0);
      std::fprintf(f, "  \"mem_bytes\": %" PRIu64 ",\n", d(&UnitStats::c_bytes));
      std::fprintf(f, "  \"mem_lines\": %" PRIu64 ",\n", d(&UnitStats::c_lines));
      std::fprintf(f, "  \"axi_bursts\": %" PRIu64 ",\n", ax.bursts - axi_before.bursts);
      std::fprintf(f, "  \"axi_beats\": %" PRIu64 ",\n", ax.beats - axi_before.beats);
      std::fprintf(f, "  \"axi_bytes\": %" PRIu64 ",\n", ax.bytes - axi_before.bytes);
      std::fprintf(f, "  \"axi_slverr_beats\": %" PRIu64 ",\n", ax.slverr - axi_before.slverr);
      std::fprintf(f, "  \"axi_decerr_beats\": %" PRIu64 ",\n", ax.decerr - axi_before.decerr);
      std::fprintf(f, "  \"axi_max_outstanding\": %" PRIu64 ",\n", ax.max_outstanding);
      std::fprintf(f, "  \"cycles_per_iteration\": %.6f,\n",
                   iters ? static_cast<double>(cycles) / iters : 0.0);
      std::fprintf(f, "  \"ray_id_stalls\": %" PRIu64 ",\n", sim.tag_stalls());
      std::fprintf(f, "  \"warm\": %s,\n", o.warm ? "true" : "false");
      std::fprintf(f, "  \"latency_min\": %u,\n", o.mem.lat_min);
      std::fprintf(f, "  \"latency_max\": %u,\n", o.mem.lat_max);
      std::fprintf(f, "  \"seed\": %" PRIu64 ",\n", o.seed);
      std::fprintf(f, "  \"sim_clocks\": %" PRIu64 ",\n", clocks);
      std::fprintf(f, "  \"wall_seconds\": %.6f,\n", wall);
      std::fprintf(f, "  \"cpu_seconds\": %.6f,\n", cpu);
      std::fprintf(f, "  \"clocks_per_cpu_second\": %.1f,\n", cps_cpu);
      std::fprintf(f, "  \"clocks_per_second\": %.1f\n", cps);
      std::fprintf(f, "}\n");
      if (std::fclose(f) != 0) fail(1, "cannot write %s", o.stats.c_str());
    }
    if (!o.quiet)
      std::printf("traverse_harness: %u rays, %" PRIu64 " iterations, %" PRIu64
                  " clocks (%.3f / iteration), cache %" PRIu64 " hits %" PRIu64
                  " misses, %" PRIu64 " bytes read; %" PRIu64 " clocks in %.3f s = %.0f clocks/s\n",
                  n, iters, cycles, iters ? static_cast<double>(cycles) / iters : 0.0, c_hits,
                  c_misses, d(&UnitStats::c_bytes), clocks, wall, cps);
  }
  return 0;
}
