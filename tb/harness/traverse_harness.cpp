// traverse_harness: a Verilator main that runs traverse_system (rtl/traverse/traverse_system.sv) on
// a whole ray batch, fast.  model/rtl_engine.py builds it (build/harness/<variant>/) and drives it.
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
// Memory model (AXI4 slave, read channels): an address accepted in clock c presents its first
// beat in clock c + L (L fixed or drawn uniformly in [min, max] per burst, L >= 1); bursts of one
// ID come back in order, bursts of different IDs in the order they become ready (never
// interleaved beat by beat); one beat per clock unless --rvalid-gap inserts bubbles; a presented
// beat is held until rready.  The memory holds the image at cfg_base and zeros around it up to
// the 4 KiB pages the image touches (so line reads of an unaligned image stay inside); beat data
// is the bus-aligned DATA_W/8-byte window; a transfer reaching outside the memory answers DECERR,
// one overlapping an --err range answers SLVERR.
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <deque>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "Vtraverse_system.h"
#include "traverse_harness.h"
#include "verilated.h"
#ifdef HARNESS_TRACE
#include "verilated_fst_c.h"
#endif

// Parameters the model was built with (model/rtl_engine.py passes them as -G and -D alike).
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

[[noreturn]] void fail(int code, const char* fmt, ...) __attribute__((format(printf, 2, 3)));
void fail(int code, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  std::fprintf(stderr, "traverse_harness: FAIL: ");
  std::vfprintf(stderr, fmt, ap);
  std::fprintf(stderr, "\n");
  va_end(ap);
  std::exit(code);
}

// xoshiro256** seeded through splitmix64.
struct Rng {
  uint64_t s[4];
  explicit Rng(uint64_t seed) {
    uint64_t z = seed;
    for (auto& w : s) {
      z += 0x9E3779B97F4A7C15ull;
      uint64_t x = z;
      x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
      x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
      w = x ^ (x >> 31);
    }
  }
  static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t next() {
    const uint64_t r = rotl(s[1] * 5, 7) * 9;
    const uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return r;
  }
  uint32_t range(uint32_t lo, uint32_t hi) {  // uniform in [lo, hi]
    if (hi <= lo) return lo;
    return lo + static_cast<uint32_t>(next() % (static_cast<uint64_t>(hi - lo) + 1));
  }
};

// A biased coin: true with probability p (no random draw at all when p == 0).
struct Coin {
  uint64_t thr = 0;
  bool on = false;
  void set(double p) {
    on = p > 0.0;
    thr = p >= 1.0 ? (1ull << 53) : static_cast<uint64_t>(p * 9007199254740992.0);
  }
  bool flip(Rng& r) const { return on && (r.next() >> 11) < thr; }
};

struct Options {
  std::string in, out, stats, waves;
  uint32_t lat_min = 20, lat_max = 20;
  uint64_t seed = 0;
  double ray_gap = 0, res_stall = 0, ar_stall = 0, rvalid_gap = 0;
  std::vector<std::pair<uint64_t, uint64_t>> err;
  uint64_t timeout = 0;
  bool warm = false, quiet = false;
};

uint64_t parse_u64(const std::string& s, const char* what) {
  char* end = nullptr;
  errno = 0;
  unsigned long long v = std::strtoull(s.c_str(), &end, 0);
  if (s.empty() || errno != 0 || *end != '\0' || s[0] == '-')
    fail(1, "bad %s '%s' (a non-negative integer)", what, s.c_str());
  return v;
}

double parse_prob(const std::string& s, const char* what) {
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !(v >= 0.0 && v <= 1.0))
    fail(1, "bad %s '%s' (a probability in [0, 1])", what, s.c_str());
  return v;
}

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
      std::string v = val("--latency");
      size_t c = v.find(':');
      if (c == std::string::npos) {
        o.lat_min = o.lat_max = static_cast<uint32_t>(parse_u64(v, "latency"));
      } else {
        o.lat_min = static_cast<uint32_t>(parse_u64(v.substr(0, c), "latency"));
        o.lat_max = static_cast<uint32_t>(parse_u64(v.substr(c + 1), "latency"));
      }
      if (o.lat_min < 1 || o.lat_max < o.lat_min || o.lat_max > 1000000)
        fail(1, "--latency: need 1 <= MIN <= MAX <= 1000000");
    } else if (a == "--seed") {
      o.seed = parse_u64(val("--seed"), "seed");
    } else if (a == "--ray-gap") {
      o.ray_gap = parse_prob(val("--ray-gap"), "--ray-gap");
    } else if (a == "--res-stall") {
      o.res_stall = parse_prob(val("--res-stall"), "--res-stall");
    } else if (a == "--ar-stall") {
      o.ar_stall = parse_prob(val("--ar-stall"), "--ar-stall");
    } else if (a == "--rvalid-gap") {
      o.rvalid_gap = parse_prob(val("--rvalid-gap"), "--rvalid-gap");
    } else if (a == "--err") {
      std::string v = val("--err");
      size_t c = v.find(':');
      if (c == std::string::npos) fail(1, "--err wants LO:HI");
      uint64_t lo = parse_u64(v.substr(0, c), "--err LO"), hi = parse_u64(v.substr(c + 1), "--err HI");
      if (hi <= lo) fail(1, "--err: empty range %s", v.c_str());
      o.err.emplace_back(lo, hi);
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
            "(model/rtl_engine.py builds it for trace_rtl(..., waves=FILE))");
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
template <typename T>
void set_bus(T& port, const uint8_t* bytes) {
  if constexpr (std::is_integral_v<T>) {
    T v = 0;
    std::memcpy(&v, bytes, kDataBytes);  // the little-endian host's byte order
    port = v;
  } else {
    for (unsigned w = 0; w < kDataBytes / 4; ++w) {
      uint32_t x;
      std::memcpy(&x, bytes + 4 * w, 4);
      port[w] = x;
    }
  }
}

struct Burst {
  uint64_t addr;      // araddr
  uint64_t ready_at;  // clock of the first beat
  uint64_t seq;       // acceptance order
  uint32_t beats, size, kind, beat;
};

struct AxiStats {
  uint64_t bursts = 0, beats = 0, bytes = 0, slverr = 0, decerr = 0, max_outstanding = 0;
};

class Memory {
 public:
  // The memory: the image at `base`, zeros around it up to the 4 KiB pages it touches.
  Memory(const std::vector<uint8_t>& img, uint64_t base, const Options& o)
      : lo_(base & ~uint64_t{4095}), hi_((base + img.size() + 4095) & ~uint64_t{4095}),
        err_(o.err), lat_min_(o.lat_min), lat_max_(o.lat_max) {
    gap_.set(o.rvalid_gap);
    mem_.assign(hi_ - lo_, 0);
    if (!img.empty()) std::memcpy(mem_.data() + (base - lo_), img.data(), img.size());
  }

  // Address channel handshake in clock `now`.
  void accept(uint32_t id, uint64_t addr, uint32_t len, uint32_t size, uint32_t kind, uint64_t now,
              Rng& rng) {
    if (kind == 3) fail(3, "AXI: reserved arburst 3 at 0x%" PRIx64, addr);
    if ((1u << size) > kDataBytes)
      fail(3, "AXI: arsize %u (%u bytes) wider than the %u-byte bus", size, 1u << size, kDataBytes);
    const uint32_t beats = len + 1;
    const uint64_t bytes = static_cast<uint64_t>(beats) << size;
    if (kind == 1 && ((addr & ~uint64_t{4095}) != (((addr & ~((uint64_t{1} << size) - 1)) + bytes - 1) & ~uint64_t{4095})))
      fail(3, "AXI: INCR burst at 0x%" PRIx64 " (%u x %u bytes) crosses a 4 KiB boundary", addr,
           beats, 1u << size);
    if (kind == 2 && (beats != 2 && beats != 4 && beats != 8 && beats != 16))
      fail(3, "AXI: WRAP burst of %u beats", beats);
    if (kind == 2 && (addr & ((1u << size) - 1)))
      fail(3, "AXI: unaligned WRAP burst at 0x%" PRIx64, addr);
    uint64_t ready = now + rng.range(lat_min_, lat_max_);
    auto& q = q_[id];
    q.push_back(Burst{addr, ready, seq_++, beats, size, kind, 0});
    ++pending_;
    ++st.bursts;
    if (pending_ > st.max_outstanding) st.max_outstanding = pending_;
  }

  // Drive the R channel for clock `now` (called with clk low, before eval).
  template <typename Top>
  void drive(Top* top, uint64_t now, Rng& rng) {
    if (presenting_) return;  // a presented beat is held until rready
    top->m_axi_rvalid = 0;
    if (active_ < 0) {
      if (pending_ == 0) return;
      const Burst* best = nullptr;
      for (unsigned i = 0; i < kAxiIds; ++i) {
        if (q_[i].empty()) continue;
        const Burst& b = q_[i].front();
        if (b.ready_at <= now && (!best || b.ready_at < best->ready_at ||
                                  (b.ready_at == best->ready_at && b.seq < best->seq))) {
          best = &b;
          active_ = static_cast<int>(i);
        }
      }
      if (active_ < 0) return;
    }
    if (gap_.flip(rng)) return;
    Burst& b = q_[active_].front();
    const uint64_t nbytes = uint64_t{1} << b.size;
    uint64_t a;  // the beat's address
    const uint64_t aligned = b.addr & ~(nbytes - 1);
    if (b.kind == 0) {
      a = b.addr;
    } else if (b.kind == 1) {
      a = b.beat == 0 ? b.addr : aligned + b.beat * nbytes;
    } else {
      const uint64_t span = b.beats * nbytes;
      const uint64_t lo = b.addr & ~(span - 1);
      a = lo + ((b.addr - lo + b.beat * nbytes) % span);
    }
    const uint64_t t_lo = a & ~(nbytes - 1), t_hi = t_lo + nbytes;  // bytes of this transfer
    uint32_t resp = 0;
    if (t_lo < lo_ || t_hi > hi_) {
      resp = 3;  // DECERR: outside the memory
    } else {
      for (const auto& r : err_)
        if (t_lo < r.second && r.first < t_hi) resp = 2;  // SLVERR: injected
    }
    const uint64_t win = a & ~uint64_t{kDataBytes - 1};  // the bus-aligned window of the beat
    if (resp == 3) {
      static const uint8_t zeros[kDataBytes] = {};
      set_bus(top->m_axi_rdata, zeros);
    } else {  // inside [lo_, hi_): pages are whole bus windows
      set_bus(top->m_axi_rdata, mem_.data() + (win - lo_));
    }
    top->m_axi_rid = static_cast<uint32_t>(active_);
    top->m_axi_rresp = resp;
    top->m_axi_rlast = b.beat + 1 == b.beats;
    top->m_axi_rvalid = 1;
    presenting_ = true;
    cur_resp_ = resp;
  }

  // The R handshake happened in clock `now`.
  void taken() {
    Burst& b = q_[active_].front();
    ++st.beats;
    st.bytes += uint64_t{1} << b.size;
    if (cur_resp_ == 2) ++st.slverr;
    if (cur_resp_ == 3) ++st.decerr;
    presenting_ = false;
    if (++b.beat == b.beats) {
      q_[active_].pop_front();
      --pending_;
      active_ = -1;
    }
  }

  bool presenting() const { return presenting_; }
  uint64_t pending() const { return pending_; }
  AxiStats st;

 private:
  uint64_t lo_, hi_;  // the memory's byte addresses [lo_, hi_)
  std::vector<uint8_t> mem_;
  std::vector<std::pair<uint64_t, uint64_t>> err_;
  uint32_t lat_min_, lat_max_;
  Coin gap_;
  std::deque<Burst> q_[kAxiIds];
  uint64_t seq_ = 0, pending_ = 0;
  int active_ = -1;
  bool presenting_ = false;
  uint32_t cur_resp_ = 0;
};

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
        mem_(in.mem, in.h.base, o) {
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
    ar_stall_.set(o.ar_stall);
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
    for (unsigned k = 0; k < trvh::kMaxLevels; ++k) t->cfg_level_off_i[k] = h.level_off[k];
    t->cfg_root_code_i = h.root_code;
    t->cfg_iter_cap_i = h.iter_cap;
    t->ray_valid_i = 0;
    t->res_ready_i = 0;
    t->m_axi_arready = 0;
    t->m_axi_rvalid = 0;
    t->clr_stats_i = 0;
    t->rst_ni = 0;
    for (int i = 0; i < 10; ++i) clock();
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
      t->m_axi_arready = !ar_stall_.flip(rng_);
      mem_.drive(t, now_, rng_);
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
        rec.flags = (t->res_hit_o ? trvh::kFlagHit : 0) | (t->res_invalid_o ? trvh::kFlagInvalid : 0) |
                    (t->res_capped_o ? trvh::kFlagCapped : 0) | (t->res_err_o ? trvh::kFlagErr : 0);
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
      mem_.drive(t, now_, rng_);
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

  // Address and data channel handshakes (sampled with clk low, after eval).
  void axi_handshakes(Vtraverse_system* t) {
    const bool arv = t->m_axi_arvalid;
    if (ar_wait_) {  // arvalid stayed high without arready last clock: payload must hold
      if (!arv || t->m_axi_araddr != ar_addr_ || t->m_axi_arid != ar_id_ ||
          t->m_axi_arlen != ar_len_ || t->m_axi_arsize != ar_size_ || t->m_axi_arburst != ar_kind_)
        fail(3, "AXI: clock %" PRIu64 ": AR request changed or withdrawn before arready", now_);
    }
    if (arv) {
      ar_addr_ = t->m_axi_araddr;
      ar_id_ = t->m_axi_arid;
      ar_len_ = t->m_axi_arlen;
      ar_size_ = t->m_axi_arsize;
      ar_kind_ = t->m_axi_arburst;
      if (t->m_axi_arready) {
        mem_.accept(ar_id_, ar_addr_, ar_len_, ar_size_, ar_kind_, now_, rng_);
        ar_wait_ = false;
      } else {
        ar_wait_ = true;
      }
    } else {
      ar_wait_ = false;
    }
    if (mem_.presenting() && t->m_axi_rready) mem_.taken();
  }

  void clock() {
    top_->clk_i = 0;
    top_->ray_valid_i = 0;
    mem_.drive(top_.get(), now_, rng_);
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
  Coin ray_gap_, res_stall_, ar_stall_;
  std::vector<uint32_t> tag_index_;
  std::vector<uint8_t> tag_busy_;
  uint64_t now_ = 0, tag_stalls_ = 0;
  bool ar_wait_ = false;
  uint64_t ar_addr_ = 0;
  uint32_t ar_id_ = 0, ar_len_ = 0, ar_size_ = 0, ar_kind_ = 0;
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
      std::fprintf(f, "  \"latency_min\": %u,\n", o.lat_min);
      std::fprintf(f, "  \"latency_max\": %u,\n", o.lat_max);
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
