// SPDX-License-Identifier: Apache-2.0
// pipeline_harness: a Verilator main that runs dm_pipeline (rtl/pipe/dm_pipeline.sv: fragments in,
// shaded pixels out) on a whole frame, fast.  tb/harness/dm_pipeline.py builds it
// (build/harness/pipeline/<variant>/) and drives it.
//
//   input file      -> configuration ports, triangle- and level-table writes, the height memory
//                      image (AXI port H), the texture memory image (AXI port T), fragments
//   fragment stream -> dm_pipeline -> pixel stream -> output file (in fragment order) + JSON stats
//
// File formats: pipeline_harness.h.  Command line: --help.
//
// What it checks, failing loudly (message on stderr, non-zero exit status):
//   - every pixel comes back exactly once (no unknown, duplicate or missing id), before --timeout
//     clocks and with never more than --stall clocks between two pixels (exit 2 on either watchdog,
//     3 on any other check); then nothing more comes out for 200 clocks and idle_o is 1;
//   - both AXI read masters keep the protocol (axi_mem.h: AR payload stable while waiting,
//     arburst not reserved, arsize within the bus, INCR bursts inside a 4 KiB page, ...);
//   - the statistics outputs agree with the pixels seen (stat_pixels_o = pixels, stat_iters_o =
//     the sum of px_iters_o).
//
// Clocking (as traverse_harness.cpp): per clock, inputs are set with clk low and evaluated, the
// handshakes are sampled (valid && ready), then the rising edge is evaluated.  Pixel ids on the
// fragment stream are the fragment's index modulo 2^PIX_W; a fragment whose id is still in flight
// waits (the stream stalls), so ids stay unique among the pixels in the unit.
//
// Memories: two AXI4 read slaves of axi_mem.h (latency fixed or random per burst, arready stalls,
// rvalid bubbles, SLVERR ranges), each with its own latency option.
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "Vdm_pipeline.h"
#include "axi_mem.h"
#include "harness_common.h"
#include "pipeline_harness.h"
#include "verilated.h"
#ifdef HARNESS_TRACE
#include "verilated_fst_c.h"
#endif

// Parameters the model was built with (tb/harness/dm_pipeline.py passes them as -G and -D alike).
#ifndef HARNESS_AXI_DATA_W
#define HARNESS_AXI_DATA_W 64
#endif
#ifndef HARNESS_H_ID_W
#define HARNESS_H_ID_W 4
#endif
#ifndef HARNESS_T_ID_W
#define HARNESS_T_ID_W 6
#endif
#ifndef HARNESS_PIX_W
#define HARNESS_PIX_W 20
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
constexpr uint32_t kPixTags = 1u << HARNESS_PIX_W;
static_assert(HARNESS_AXI_DATA_W >= 8 && (HARNESS_AXI_DATA_W & (HARNESS_AXI_DATA_W - 1)) == 0,
              "AXI data width is a power of two");
static_assert(HARNESS_PIX_W >= 8 && HARNESS_PIX_W <= 24, "pixel id width 8 .. 24");
static_assert(HARNESS_H_ID_W >= 1 && HARNESS_H_ID_W <= 8, "AXI id width 1 .. 8");
static_assert(HARNESS_T_ID_W >= 1 && HARNESS_T_ID_W <= 8, "AXI id width 1 .. 8");

using HeightMemory = harness::AxiReadSlave<kDataBytes, 1u << HARNESS_H_ID_W>;
using TextureMemory = harness::AxiReadSlave<kDataBytes, 1u << HARNESS_T_ID_W>;

const char* kUsage = R"(usage: pipeline_harness --in FILE --out FILE [options]

Runs dm_pipeline (fragments -> view unit -> traverse unit + height cache -> MIP level -> texture
cache -> filter -> shading -> pixels) on a frame, with two AXI4 memory models (heights, textures).

  --in FILE           input: configuration, triangle table, memory images, fragments
                      (tb/harness/pipeline_harness.h)
  --out FILE          output: one record per fragment, in fragment order
  --stats FILE        JSON statistics (cycles, pixels, iterations, cache hits, bytes, ...)
  --latency L         AXI read latency of both ports: first beat L clocks after the address
                      (default 20)
  --latency MIN:MAX   ... drawn uniformly per burst in [MIN, MAX] (MIN >= 1)
  --h-latency L|MIN:MAX, --t-latency L|MIN:MAX   the same for one port (height / texture)
  --seed S            seed of every random choice below and of the model's X values (default 0)
  --frag-gap P        probability that the fragment stream offers nothing in a clock (default 0)
  --px-stall P        probability that px_ready is low in a clock (default 0)
  --ar-stall P        probability that arready is low in a clock, both ports (default 0)
  --rvalid-gap P      probability of a bubble before a read beat, both ports (default 0)
  --reset N           clocks rst_ni is held low at the start, N >= 1 (default 10); the registers
                      start from the seed's random values, so a short reset shows any state
                      that a reset leaves to chance
  --h-err LO:HI, --t-err LO:HI   byte addresses [LO, HI) of that port answer SLVERR; repeatable
  --timeout N         fail (exit 2) when the frame takes more than N clocks
                      (default 2000000 + 2000 per fragment)
  --stall N           fail (exit 2) when no pixel comes out for N clocks
                      (default 2000000 + 100 x the iteration cap)
  --progress          print "progress DONE TOTAL CLOCKS" lines on stdout about twice a second
  --waves FILE.fst    write an FST waveform (only the waves variant of the binary has tracing)
  --quiet             no summary line on stdout
  --help              this text

Exit status: 0 every pixel back exactly once; 1 usage or file error; 2 a watchdog (--timeout,
--stall); 3 a failed check (unknown / duplicate / missing pixel id, an extra pixel, not idle at
the end, AXI protocol violation, statistics that disagree with the pixels).
)";

struct Options {
  std::string in, out, stats, waves;
  AxiMemConfig hmem, tmem;
  uint64_t seed = 0;
  double frag_gap = 0, px_stall = 0;
  uint64_t timeout = 0, stall = 0;
  uint64_t reset = 10;
  bool progress = false, quiet = false;
};

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
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
      const auto lat = harness::parse_latency(val("--latency"), "--latency");
      std::tie(o.hmem.lat_min, o.hmem.lat_max) = lat;
      std::tie(o.tmem.lat_min, o.tmem.lat_max) = lat;
    } else if (a == "--h-latency") {
      std::tie(o.hmem.lat_min, o.hmem.lat_max) =
          harness::parse_latency(val("--h-latency"), "--h-latency");
    } else if (a == "--t-latency") {
      std::tie(o.tmem.lat_min, o.tmem.lat_max) =
          harness::parse_latency(val("--t-latency"), "--t-latency");
    } else if (a == "--seed") {
      o.seed = parse_u64(val("--seed"), "seed");
    } else if (a == "--frag-gap") {
      o.frag_gap = parse_prob(val("--frag-gap"), "--frag-gap");
    } else if (a == "--px-stall") {
      o.px_stall = parse_prob(val("--px-stall"), "--px-stall");
    } else if (a == "--ar-stall") {
      o.hmem.ar_stall = o.tmem.ar_stall = parse_prob(val("--ar-stall"), "--ar-stall");
    } else if (a == "--rvalid-gap") {
      o.hmem.rvalid_gap = o.tmem.rvalid_gap = parse_prob(val("--rvalid-gap"), "--rvalid-gap");
    } else if (a == "--h-err") {
      o.hmem.err.push_back(harness::parse_range(val("--h-err"), "--h-err"));
    } else if (a == "--t-err") {
      o.tmem.err.push_back(harness::parse_range(val("--t-err"), "--t-err"));
    } else if (a == "--reset") {
      o.reset = parse_u64(val("--reset"), "reset");
      if (o.reset < 1) fail(1, "--reset wants at least 1 clock");
    } else if (a == "--timeout") {
      o.timeout = parse_u64(val("--timeout"), "timeout");
    } else if (a == "--stall") {
      o.stall = parse_u64(val("--stall"), "stall");
    } else if (a == "--progress") {
      o.progress = true;
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
            "(tb/harness/dm_pipeline.py builds it for run_frame(..., waves=FILE))");
#endif
  return o;
}

// ---- input ---------------------------------------------------------------------------------

struct Input {
  piph::InHeader h;
  std::vector<std::vector<uint32_t>> cfg;  // per port of PIPH_CFG_PORTS: its value's words
  std::vector<piph::TableWrite> tri, lvt;
  std::vector<uint8_t> himg, timg;
  std::vector<piph::Fragment> frags;
};

class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path), f_(std::fopen(path.c_str(), "rb")) {
    if (!f_) fail(1, "cannot open input %s: %s", path.c_str(), std::strerror(errno));
  }
  ~Reader() {
    if (f_) std::fclose(f_);
  }
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  void read(void* dst, size_t bytes, const char* what) {
    if (bytes && std::fread(dst, bytes, 1, f_) != 1) fail(1, "%s: short %s", path_.c_str(), what);
  }
  uint32_t word(const char* what) {
    uint32_t w;
    read(&w, 4, what);
    return w;
  }
  // An image of `bytes` bytes, zero-padded in the file to a multiple of 4.
  std::vector<uint8_t> image(uint32_t bytes, const char* what) {
    std::vector<uint8_t> v((static_cast<size_t>(bytes) + 3) & ~size_t{3});
    read(v.data(), v.size(), what);
    v.resize(bytes);
    return v;
  }
  void expect_end() {
    char extra;
    if (std::fread(&extra, 1, 1, f_) != 0)
      fail(1, "%s: trailing bytes after the fragments", path_.c_str());
  }

 private:
  std::string path_;
  FILE* f_;
};

const char* const kCfgNames[] = {
#define PIPH_NAME(name, bits) #name,
    PIPH_CFG_PORTS(PIPH_NAME)
#undef PIPH_NAME
};
const uint32_t kCfgBits[] = {
#define PIPH_BITS(name, bits) bits,
    PIPH_CFG_PORTS(PIPH_BITS)
#undef PIPH_BITS
};

Input read_input(const std::string& path) {
  Input in;
  Reader r(path);
  r.read(&in.h, sizeof in.h, "header");
  const auto& h = in.h;
  if (std::memcmp(h.magic, piph::kInMagic, 8) != 0)
    fail(1, "%s: not a pipeline harness input file", path.c_str());
  if (h.version != piph::kInVersion || h.header_bytes != sizeof(piph::InHeader))
    fail(1, "%s: version %u / header %u bytes, this harness reads version %u / %zu bytes",
         path.c_str(), h.version, h.header_bytes, piph::kInVersion, sizeof(piph::InHeader));
  if (h.n_cfg_ports != piph::kCfgPorts || h.frag_words != piph::kFragWords)
    fail(1, "%s: %u configuration ports / %u words per fragment, this harness has %u / %u",
         path.c_str(), h.n_cfg_ports, h.frag_words, piph::kCfgPorts, piph::kFragWords);
  uint32_t words = 0;
  for (uint32_t k = 0; k < piph::kCfgPorts; ++k) {
    const uint32_t bits = r.word("configuration");
    if (bits != kCfgBits[k])
      fail(1, "%s: configuration port %u (%s) has %u bits in the file, %u in this harness",
           path.c_str(), k, kCfgNames[k], bits, kCfgBits[k]);
    std::vector<uint32_t> v((bits + 31) / 32);
    r.read(v.data(), 4 * v.size(), "configuration");
    if (bits % 32 && (v.back() >> (bits % 32)) != 0)
      fail(1, "%s: %s = a value wider than its %u bits", path.c_str(), kCfgNames[k], bits);
    words += 1 + static_cast<uint32_t>(v.size());
    in.cfg.push_back(std::move(v));
  }
  if (words != h.cfg_words)
    fail(1, "%s: configuration of %u words, the header says %u", path.c_str(), words, h.cfg_words);
  in.tri.resize(h.n_tri_writes);
  r.read(in.tri.data(), sizeof(piph::TableWrite) * in.tri.size(), "triangle-table writes");
  in.lvt.resize(h.n_lvt_writes);
  r.read(in.lvt.data(), sizeof(piph::TableWrite) * in.lvt.size(), "level-table writes");
  in.himg = r.image(h.h_bytes, "height image");
  in.timg = r.image(h.t_bytes, "texture image");
  if (uint64_t{h.h_base} + h.h_bytes > (uint64_t{1} << 32) ||
      uint64_t{h.t_base} + h.t_bytes > (uint64_t{1} << 32))
    fail(1, "%s: a memory image reaches past the 32-bit address space", path.c_str());
  in.frags.resize(h.n_frags);
  r.read(in.frags.data(), sizeof(piph::Fragment) * in.frags.size(), "fragment list");
  r.expect_end();
  return in;
}

// ---- the simulation ------------------------------------------------------------------------

struct UnitStats {
  uint64_t cycles, pixels, iters, h_hits, h_misses, h_bytes, t_requests, t_quad_hits,
      t_line_misses, t_texel_hits, t_bytes;
};

UnitStats snapshot(const Vdm_pipeline* t) {
  return UnitStats{t->stat_cycles_o,     t->stat_pixels_o,     t->stat_iters_o,
                   t->stat_h_hits_o,     t->stat_h_misses_o,   t->stat_h_bytes_o,
                   t->stat_t_requests_o, t->stat_t_quad_hits_o, t->stat_t_line_misses_o,
                   t->stat_t_texel_hits_o, t->stat_t_bytes_o};
}

// Pack 24-bit words, element i at bits [24 i +: 24], into a wide port.
template <typename T, size_t N>
void set_f24_array(T& port, const uint32_t (&w)[N]) {
  uint8_t bytes[3 * N];
  for (size_t i = 0; i < N; ++i) {
    bytes[3 * i] = static_cast<uint8_t>(w[i]);
    bytes[3 * i + 1] = static_cast<uint8_t>(w[i] >> 8);
    bytes[3 * i + 2] = static_cast<uint8_t>(w[i] >> 16);
  }
  harness::set_bytes(port, bytes, 3 * N);
}

class Sim {
 public:
  Sim(const Input& in, const Options& o)
      : in_(in), o_(o), rng_(o.seed * 0x9E3779B97F4A7C15ull + 1),
        hmem_("AXI heights", in.himg, in.h.h_base, o.hmem),
        tmem_("AXI textures", in.timg, in.h.t_base, o.tmem) {
    ctx_ = std::make_unique<VerilatedContext>();
    ctx_->randReset(2);
    ctx_->randSeed(static_cast<int>(o.seed & 0x7FFFFFFF));
#ifdef HARNESS_TRACE
    if (!o.waves.empty()) ctx_->traceEverOn(true);
#endif
    top_ = std::make_unique<Vdm_pipeline>(ctx_.get(), "TOP");
#ifdef HARNESS_TRACE
    if (!o.waves.empty()) {
      fst_ = std::make_unique<VerilatedFstC>();
      top_->trace(fst_.get(), 99);
      fst_->open(o.waves.c_str());
    }
#endif
    frag_gap_.set(o.frag_gap);
    px_stall_.set(o.px_stall);
    tag_index_.assign(kPixTags, 0);
    tag_busy_.assign(kPixTags, 0);
  }

  ~Sim() {
#ifdef HARNESS_TRACE
    if (fst_) fst_->close();
#endif
    top_->final();
  }

  Sim(const Sim&) = delete;
  Sim& operator=(const Sim&) = delete;

  // Configuration ports, reset, the triangle- and level-table writes.
  void configure_and_reset() {
    auto* t = top_.get();
    size_t k = 0;
#define PIPH_SET(name, bits)                                                                      \
  static_assert(harness::port_words<std::remove_reference_t<decltype(Vdm_pipeline::name)>>() ==   \
                    ((bits) + 31) / 32,                                                           \
                #name ": the harness table's width does not match the Verilated port");           \
  harness::set_bytes(t->name, reinterpret_cast<const uint8_t*>(in_.cfg[k].data()),                \
                     static_cast<unsigned>(4 * in_.cfg[k].size()));                               \
  ++k;
    PIPH_CFG_PORTS(PIPH_SET)
#undef PIPH_SET
    iter_cap_ = t->cfg_iter_cap_i;
    t->frag_valid_i = 0;
    t->px_ready_i = 0;
    t->tt_we_i = 0;
    t->lvt_we_i = 0;
    t->clr_stats_i = 0;
    t->m_axi_h_arready = 0;
    t->m_axi_t_arready = 0;
    t->m_axi_h_rvalid = 0;
    t->m_axi_t_rvalid = 0;
    t->rst_ni = 0;
    for (uint64_t i = 0; i < o_.reset; ++i) clock();
    t->rst_ni = 1;
    for (const auto& w : in_.tri) {
      t->tt_we_i = 1;
      t->tt_waddr_i = w.addr;
      t->tt_wdata_i = w.data & 0xFFFFFF;
      clock();
    }
    t->tt_we_i = 0;
    for (const auto& w : in_.lvt) {
      t->lvt_we_i = 1;
      t->lvt_waddr_i = w.addr;
      t->lvt_wdata_i = w.data;
      clock();
    }
    t->lvt_we_i = 0;
    for (int i = 0; i < 8; ++i) clock();  // the configuration settles (>= 4 clocks)
  }

  // The whole frame; records land in `out` (fragment order).  Returns the clocks from the first
  // fragment in to the last pixel out.
  uint64_t run(std::vector<piph::OutRecord>& out) {
    auto* t = top_.get();
    const uint32_t n = in_.h.n_frags;
    out.assign(n, piph::OutRecord{});
    std::vector<uint8_t> seen(n, 0);
    const uint64_t timeout = o_.timeout ? o_.timeout : 2000000ull + 2000ull * n;
    const uint64_t stall = o_.stall ? o_.stall : 2000000ull + 100ull * iter_cap_;
    uint32_t next = 0, cur_tag = 0;
    bool presenting = false;
    const uint64_t start = now_;
    uint64_t first_in = 0, last_out = now_;
    auto wall0 = std::chrono::steady_clock::now();
    auto last_report = wall0;
    while (done_ < n) {
      if (now_ - start >= timeout) watchdog(n, next, "timeout", timeout, "--timeout");
      if (now_ - last_out >= stall) watchdog(n, next, "no pixel came out for", stall, "--stall");
      if (o_.progress && (now_ & 16383) == 0) {
        const auto w = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(w - last_report).count() >= 0.5) {
          std::printf("progress %u %u %" PRIu64 "\n", done_, n, now_ - start);
          std::fflush(stdout);
          last_report = w;
        }
      }
      // ---- inputs of this clock (clk low) ----
      t->clk_i = 0;
      if (!presenting && next < n && !frag_gap_.flip(rng_)) {
        cur_tag = next & (kPixTags - 1);
        if (!tag_busy_[cur_tag]) {
          const piph::Fragment& f = in_.frags[next];
          t->frag_id_i = cur_tag;
          t->frag_u0_i = f.u0 & 0xFFFFFF;
          t->frag_v0_i = f.v0 & 0xFFFFFF;
          t->frag_pl0_i = f.pl0 & 0xFFFFFF;
          t->frag_tri_i = f.tri;
          set_f24_array(t->frag_tbn_i, f.tbn);
          set_f24_array(t->frag_view_i, f.view);
          presenting = true;
        } else {
          ++tag_stalls_;
        }
      }
      t->frag_valid_i = presenting;
      t->px_ready_i = !px_stall_.flip(rng_);
      t->m_axi_h_arready = hmem_.draw_arready(rng_);
      t->m_axi_t_arready = tmem_.draw_arready(rng_);
      drive_r();
      t->eval();
      dump(2 * now_);
      // ---- handshakes of this clock ----
      if (presenting && t->frag_ready_o) {
        if (next == 0) first_in = now_;
        tag_busy_[cur_tag] = 1;
        tag_index_[cur_tag] = next;
        ++next;
        presenting = false;
      }
      if (t->px_valid_o && t->px_ready_i) {
        const uint32_t tag = t->px_id_o;
        if (!tag_busy_[tag])
          fail(3, "clock %" PRIu64 ": pixel with id %u, which is not in flight (a duplicate or "
                  "an id never sent)", now_, tag);
        const uint32_t idx = tag_index_[tag];
        if (seen[idx]) fail(3, "pixel %u returned twice", idx);
        seen[idx] = 1;
        tag_busy_[tag] = 0;
        piph::OutRecord& rec = out[idx];
        rec.id = idx;
        rec.rgb = t->px_rgb_o & 0xFFFFFF;
        rec.flags = (t->px_hit_o ? uint32_t{piph::kFlagHit} : 0u) |
                    (t->px_invalid_o ? uint32_t{piph::kFlagInvalid} : 0u) |
                    (t->px_err_o ? uint32_t{piph::kFlagErr} : 0u);
        rec.iterations = t->px_iters_o;
        ++done_;
        last_out = now_;
      }
      axi_handshakes();
      // ---- rising edge ----
      t->clk_i = 1;
      t->eval();
      dump(2 * now_ + 1);
      ++now_;
    }
    for (uint32_t i = 0; i < n; ++i)
      if (!seen[i]) fail(3, "pixel %u never came back", i);
    // Nothing more may come out, and the unit is idle.
    t->frag_valid_i = 0;
    for (int i = 0; i < 200; ++i) {
      t->clk_i = 0;
      t->px_ready_i = 1;
      drive_r();
      t->eval();
      dump(2 * now_);
      if (t->px_valid_o)
        fail(3, "an extra pixel (id %u) after every pixel came back",
             static_cast<unsigned>(t->px_id_o));
      axi_handshakes();
      t->clk_i = 1;
      t->eval();
      dump(2 * now_ + 1);
      ++now_;
    }
    if (!t->idle_o) fail(3, "idle_o is 0 after every pixel came back");
    t->px_ready_i = 0;
    return n ? last_out - first_in + 1 : 0;
  }

  uint64_t now() const { return now_; }
  uint64_t tag_stalls() const { return tag_stalls_; }
  const HeightMemory& hmem() const { return hmem_; }
  const TextureMemory& tmem() const { return tmem_; }
  const Vdm_pipeline* top() const { return top_.get(); }

 private:
  void dump(uint64_t ts) {
#ifdef HARNESS_TRACE
    if (fst_) fst_->dump(ts);
#else
    (void)ts;
#endif
  }

  // Both memories' R channels of this clock (clk low, before eval).
  void drive_r() {
    auto* t = top_.get();
    harness::drive_r<kDataBytes>(hmem_.drive(now_, rng_), t->m_axi_h_rid, t->m_axi_h_rdata,
                                 t->m_axi_h_rresp, t->m_axi_h_rlast, t->m_axi_h_rvalid);
    harness::drive_r<kDataBytes>(tmem_.drive(now_, rng_), t->m_axi_t_rid, t->m_axi_t_rdata,
                                 t->m_axi_t_rresp, t->m_axi_t_rlast, t->m_axi_t_rvalid);
  }

  // Address and data channel handshakes of both ports (sampled with clk low, after eval).
  void axi_handshakes() {
    auto* t = top_.get();
    hmem_.handshakes(harness::ArSignals{static_cast<bool>(t->m_axi_h_arvalid), t->m_axi_h_arid,
                                        t->m_axi_h_araddr, t->m_axi_h_arlen, t->m_axi_h_arsize,
                                        t->m_axi_h_arburst},
                     t->m_axi_h_arready, t->m_axi_h_rready, now_, rng_);
    tmem_.handshakes(harness::ArSignals{static_cast<bool>(t->m_axi_t_arvalid), t->m_axi_t_arid,
                                        t->m_axi_t_araddr, t->m_axi_t_arlen, t->m_axi_t_arsize,
                                        t->m_axi_t_arburst},
                     t->m_axi_t_arready, t->m_axi_t_rready, now_, rng_);
  }

  void clock() {
    top_->clk_i = 0;
    top_->frag_valid_i = 0;
    drive_r();
    top_->eval();
    dump(2 * now_);
    axi_handshakes();
    top_->clk_i = 1;
    top_->eval();
    dump(2 * now_ + 1);
    ++now_;
  }

  [[noreturn]] void watchdog(uint32_t n, uint32_t next, const char* what, uint64_t limit,
                             const char* option) {
    std::fprintf(stderr,
                 "pipeline_harness: %u of %u pixels back, %u fragments sent, clock %" PRIu64
                 " (idle_o=%d, frag_ready_o=%d, px_valid_o=%d, AXI bursts pending: heights %" PRIu64
                 ", textures %" PRIu64 ")\n",
                 done_, n, next, now_, static_cast<int>(top_->idle_o),
                 static_cast<int>(top_->frag_ready_o), static_cast<int>(top_->px_valid_o),
                 hmem_.pending(), tmem_.pending());
    unsigned shown = 0;
    for (uint32_t tag = 0; tag < kPixTags && shown < 10; ++tag)
      if (tag_busy_[tag]) {
        std::fprintf(stderr, "  still in flight: pixel %u (id %u)\n", tag_index_[tag], tag);
        ++shown;
      }
#ifdef HARNESS_TRACE
    if (fst_) fst_->close();
    fst_.reset();
#endif
    fail(2, "%s %" PRIu64 " clocks (%s)", what, limit, option);
  }

  const Input& in_;
  const Options& o_;
  Rng rng_;
  HeightMemory hmem_;
  TextureMemory tmem_;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Vdm_pipeline> top_;
#ifdef HARNESS_TRACE
  std::unique_ptr<VerilatedFstC> fst_;
#endif
  Coin frag_gap_, px_stall_;
  std::vector<uint32_t> tag_index_;
  std::vector<uint8_t> tag_busy_;
  uint64_t now_ = 0, tag_stalls_ = 0;
  uint32_t done_ = 0, iter_cap_ = 0;
};

void write_output(const std::string& path, const std::vector<piph::OutRecord>& out) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) fail(1, "cannot write %s: %s", path.c_str(), std::strerror(errno));
  piph::OutHeader h{};
  std::memcpy(h.magic, piph::kOutMagic, 8);
  h.n_frags = static_cast<uint32_t>(out.size());
  h.record_bytes = sizeof(piph::OutRecord);
  bool ok = std::fwrite(&h, sizeof h, 1, f) == 1;
  if (!out.empty())
    ok = ok && std::fwrite(out.data(), sizeof(piph::OutRecord), out.size(), f) == out.size();
  if (std::fclose(f) != 0 || !ok) fail(1, "cannot write %s", path.c_str());
}

double ratio(uint64_t a, uint64_t b) {
  return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0;
}

void write_axi(FILE* f, const char* port, const AxiStats& s, const AxiMemConfig& c) {
  std::fprintf(f, "  \"axi_%s_bursts\": %" PRIu64 ",\n", port, s.bursts);
  std::fprintf(f, "  \"axi_%s_beats\": %" PRIu64 ",\n", port, s.beats);
  std::fprintf(f, "  \"axi_%s_bytes\": %" PRIu64 ",\n", port, s.bytes);
  std::fprintf(f, "  \"axi_%s_slverr_beats\": %" PRIu64 ",\n", port, s.slverr);
  std::fprintf(f, "  \"axi_%s_decerr_beats\": %" PRIu64 ",\n", port, s.decerr);
  std::fprintf(f, "  \"axi_%s_max_outstanding\": %" PRIu64 ",\n", port, s.max_outstanding);
  std::fprintf(f, "  \"%s_latency_min\": %u,\n", port, c.lat_min);
  std::fprintf(f, "  \"%s_latency_max\": %u,\n", port, c.lat_max);
}

}  // namespace

int main(int argc, char** argv) {
  harness::set_name("pipeline_harness");
  const Options o = parse_args(argc, argv);
  const Input in = read_input(o.in);
  const uint32_t n = in.h.n_frags;

  const auto t0 = std::chrono::steady_clock::now();
  std::vector<piph::OutRecord> out;
  Sim sim(in, o);
  sim.configure_and_reset();
  const UnitStats before = snapshot(sim.top());
  const uint64_t cycles = sim.run(out);
  const UnitStats after = snapshot(sim.top());
  const uint64_t clocks = sim.now();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  uint64_t iters = 0, hits = 0, invalid = 0, err = 0;
  for (const auto& r : out) {
    iters += r.iterations;
    hits += (r.flags & piph::kFlagHit) != 0;
    invalid += (r.flags & piph::kFlagInvalid) != 0;
    err += (r.flags & piph::kFlagErr) != 0;
  }
  auto d = [&](uint64_t UnitStats::*f) { return after.*f - before.*f; };
  if (d(&UnitStats::pixels) != n)
    fail(3, "stat_pixels_o counted %" PRIu64 " pixels, %u came out", d(&UnitStats::pixels), n);
  if (d(&UnitStats::iters) != iters)
    fail(3, "stat_iters_o counted %" PRIu64 " iterations, the pixels carry %" PRIu64,
         d(&UnitStats::iters), iters);
  write_output(o.out, out);

  const uint64_t h_hits = d(&UnitStats::h_hits), h_misses = d(&UnitStats::h_misses);
  const uint64_t t_req = d(&UnitStats::t_requests), t_qh = d(&UnitStats::t_quad_hits);
  const uint64_t t_th = d(&UnitStats::t_texel_hits);
  const uint64_t h_bytes = d(&UnitStats::h_bytes), t_bytes = d(&UnitStats::t_bytes);
  const double cps = wall > 0 ? static_cast<double>(clocks) / wall : 0.0;
  if (!o.stats.empty()) {
    FILE* f = std::fopen(o.stats.c_str(), "w");
    if (!f) fail(1, "cannot write %s: %s", o.stats.c_str(), std::strerror(errno));
    std::fprintf(f, "{\n");
    std::fprintf(f, "  \"pixels\": %u,\n", n);
    std::fprintf(f, "  \"cycles\": %" PRIu64 ",\n", cycles);
    std::fprintf(f, "  \"busy_cycles\": %" PRIu64 ",\n", d(&UnitStats::cycles));
    std::fprintf(f, "  \"iterations\": %" PRIu64 ",\n", iters);
    std::fprintf(f, "  \"hits\": %" PRIu64 ",\n", hits);
    std::fprintf(f, "  \"invalid\": %" PRIu64 ",\n", invalid);
    std::fprintf(f, "  \"errors\": %" PRIu64 ",\n", err);
    std::fprintf(f, "  \"height_cache_hits\": %" PRIu64 ",\n", h_hits);
    std::fprintf(f, "  \"height_cache_misses\": %" PRIu64 ",\n", h_misses);
    std::fprintf(f, "  \"height_cache_hit_rate\": %.6f,\n", ratio(h_hits, h_hits + h_misses));
    std::fprintf(f, "  \"height_mem_bytes\": %" PRIu64 ",\n", h_bytes);
    std::fprintf(f, "  \"texture_requests\": %" PRIu64 ",\n", t_req);
    std::fprintf(f, "  \"texture_quad_hits\": %" PRIu64 ",\n", t_qh);
    std::fprintf(f, "  \"texture_texel_hits\": %" PRIu64 ",\n", t_th);
    // per texel access (four per quad), the usual measure of a texture cache; the quad rate is
    // the stricter one (all four texels' lines present)
    std::fprintf(f, "  \"texture_cache_hit_rate\": %.6f,\n", ratio(t_th, 4 * t_req));
    std::fprintf(f, "  \"texture_quad_hit_rate\": %.6f,\n", ratio(t_qh, t_req));
    std::fprintf(f, "  \"texture_line_misses\": %" PRIu64 ",\n", d(&UnitStats::t_line_misses));
    std::fprintf(f, "  \"texture_mem_bytes\": %" PRIu64 ",\n", t_bytes);
    std::fprintf(f, "  \"mem_bytes\": %" PRIu64 ",\n", h_bytes + t_bytes);
    write_axi(f, "h", sim.hmem().st, o.hmem);
    write_axi(f, "t", sim.tmem().st, o.tmem);
    std::fprintf(f, "  \"cycles_per_pixel\": %.6f,\n", ratio(cycles, n));
    std::fprintf(f, "  \"pixel_id_stalls\": %" PRIu64 ",\n", sim.tag_stalls());
    std::fprintf(f, "  \"seed\": %" PRIu64 ",\n", o.seed);
    std::fprintf(f, "  \"sim_clocks\": %" PRIu64 ",\n", clocks);
    std::fprintf(f, "  \"wall_seconds\": %.6f,\n", wall);
    std::fprintf(f, "  \"clocks_per_second\": %.1f\n", cps);
    std::fprintf(f, "}\n");
    if (std::fclose(f) != 0) fail(1, "cannot write %s", o.stats.c_str());
  }
  if (!o.quiet)
    std::printf("pipeline_harness: %u pixels, %" PRIu64 " hits, %" PRIu64 " iterations, %" PRIu64
                " clocks (%.3f / pixel), height cache %.4f, texture cache %.4f, %" PRIu64
                " bytes read; %" PRIu64 " clocks in %.3f s = %.0f clocks/s\n",
                n, hits, iters, cycles, ratio(cycles, n), ratio(h_hits, h_hits + h_misses),
                ratio(t_qh, t_req), h_bytes + t_bytes, clocks, wall, cps);
  return 0;
}
