// SPDX-License-Identifier: Apache-2.0
// axi_mem.h: the AXI4 read-slave memory model of the Verilator harnesses (traverse_harness.cpp,
// pipeline_harness.cpp), with a protocol check of the read master's address channel.
//
// Memory model (read channels only): an address accepted in clock c presents its first beat in
// clock c + L (L fixed or drawn uniformly in [min, max] per burst, L >= 1); bursts of one ID come
// back in order, bursts of different IDs in the order they become ready (never interleaved beat by
// beat); one beat per clock unless the rvalid-gap coin inserts bubbles; a presented beat is held
// until rready.  The memory holds an image at a base address and zeros around it up to the 4 KiB
// pages the image touches (so line reads of an unaligned image stay inside); beat data is the
// bus-aligned DataBytes window; a transfer reaching outside the memory answers DECERR, one
// overlapping an error range answers SLVERR.
//
// Checks (harness::fail with status 3): AR payload stable while arvalid waits for arready,
// arburst not reserved, arsize within the bus, INCR bursts inside a 4 KiB page, WRAP bursts of
// 2, 4, 8 or 16 beats and aligned.
//
// Use per clock, with the clock low:
//   arready = slave.draw_arready(rng);  const RBeat& r = slave.drive(now, rng);  (set the ports)
//   eval();  slave.handshakes(ar_signals, arready, rready, now, rng);  then the rising edge.
#pragma once

#include <cinttypes>
#include <cstdint>
#include <cstring>
#include <deque>
#include <utility>
#include <vector>

#include "harness_common.h"

namespace harness {

struct AxiMemConfig {
  uint32_t lat_min = 20, lat_max = 20;  // read latency, clocks from the address to the first beat
  double rvalid_gap = 0;                // probability of a bubble before a beat
  double ar_stall = 0;                  // probability that arready is low in a clock
  std::vector<std::pair<uint64_t, uint64_t>> err;  // byte ranges [lo, hi) answering SLVERR
};

struct AxiStats {
  uint64_t bursts = 0, beats = 0, bytes = 0, slverr = 0, decerr = 0, max_outstanding = 0;
};

// The address channel as the master drives it in this clock.
struct ArSignals {
  bool valid;
  uint32_t id;
  uint64_t addr;
  uint32_t len, size, burst;
};

// The read-data channel as the slave drives it in this clock (data: DataBytes bytes).
struct RBeat {
  bool valid = false;
  uint32_t id = 0, resp = 0;
  bool last = false;
  const uint8_t* data = nullptr;
};

template <unsigned DataBytes, unsigned Ids>
class AxiReadSlave {
  static_assert(DataBytes >= 1 && (DataBytes & (DataBytes - 1)) == 0, "bus bytes: a power of two");

 public:
  // `name` prefixes protocol failures ("AXI", "AXI heights", ...).
  AxiReadSlave(const char* name, const std::vector<uint8_t>& img, uint64_t base,
               const AxiMemConfig& c)
      : name_(name), lo_(base & ~uint64_t{4095}),
        hi_((base + img.size() + 4095) & ~uint64_t{4095}), err_(c.err), lat_min_(c.lat_min),
        lat_max_(c.lat_max) {
    gap_.set(c.rvalid_gap);
    stall_.set(c.ar_stall);
    mem_.assign(hi_ - lo_, 0);
    if (!img.empty()) std::memcpy(mem_.data() + (base - lo_), img.data(), img.size());
  }

  // arready of this clock.
  bool draw_arready(Rng& rng) const { return !stall_.flip(rng); }

  // The R channel of clock `now` (called with the clock low, before eval).  A presented beat is
  // held until rready.
  const RBeat& drive(uint64_t now, Rng& rng) {
    if (beat_.valid) return beat_;
    if (active_ < 0) {
      if (pending_ == 0) return beat_;
      const Burst* best = nullptr;
      for (unsigned i = 0; i < Ids; ++i) {
        if (q_[i].empty()) continue;
        const Burst& b = q_[i].front();
        if (b.ready_at <= now && (!best || b.ready_at < best->ready_at ||
                                  (b.ready_at == best->ready_at && b.seq < best->seq))) {
          best = &b;
          active_ = static_cast<int>(i);
        }
      }
      if (active_ < 0) return beat_;
    }
    if (gap_.flip(rng)) return beat_;
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
    const uint64_t win = a & ~uint64_t{DataBytes - 1};  // the bus-aligned window of the beat
    static const uint8_t zeros[DataBytes] = {};
    beat_.data = resp == 3 ? zeros : mem_.data() + (win - lo_);  // pages are whole bus windows
    beat_.id = static_cast<uint32_t>(active_);
    beat_.resp = resp;
    beat_.last = b.beat + 1 == b.beats;
    beat_.valid = true;
    return beat_;
  }

  // The handshakes of clock `now` (sampled with the clock low, after eval): the AR channel as
  // the master drives it with the arready given, and the R beat if rready.
  void handshakes(const ArSignals& ar, bool arready, bool rready, uint64_t now, Rng& rng) {
    if (ar_wait_) {  // arvalid stayed high without arready last clock: payload must hold
      if (!ar.valid || ar.addr != ar_.addr || ar.id != ar_.id || ar.len != ar_.len ||
          ar.size != ar_.size || ar.burst != ar_.burst)
        fail(3, "%s: clock %" PRIu64 ": AR request changed or withdrawn before arready", name_,
             now);
    }
    if (ar.valid) {
      ar_ = ar;
      if (arready) {
        accept(ar, now, rng);
        ar_wait_ = false;
      } else {
        ar_wait_ = true;
      }
    } else {
      ar_wait_ = false;
    }
    if (beat_.valid && rready) taken();
  }

  uint64_t pending() const { return pending_; }
  // Byte access for a write port that shares this memory: false outside [lo, hi).
  bool poke(uint64_t a, uint8_t v) {
    if (a < lo_ || a >= hi_) return false;
    mem_[a - lo_] = v;
    return true;
  }
  uint8_t peek(uint64_t a) const { return (a >= lo_ && a < hi_) ? mem_[a - lo_] : 0; }
  AxiStats st;

 private:
  struct Burst {
    uint64_t addr;      // araddr
    uint64_t ready_at;  // clock of the first beat
    uint64_t seq;       // acceptance order
    uint32_t beats, size, kind, beat;
  };

  void accept(const ArSignals& ar, uint64_t now, Rng& rng) {
    const uint64_t addr = ar.addr;
    if (ar.id >= Ids) fail(3, "%s: arid %u beyond the %u IDs", name_, ar.id, Ids);
    if (ar.burst == 3) fail(3, "%s: reserved arburst 3 at 0x%" PRIx64, name_, addr);
    if ((1u << ar.size) > DataBytes)
      fail(3, "%s: arsize %u (%u bytes) wider than the %u-byte bus", name_, ar.size,
           1u << ar.size, DataBytes);
    const uint32_t beats = ar.len + 1;
    const uint64_t bytes = static_cast<uint64_t>(beats) << ar.size;
    if (ar.burst == 1 &&
        ((addr & ~uint64_t{4095}) !=
         (((addr & ~((uint64_t{1} << ar.size) - 1)) + bytes - 1) & ~uint64_t{4095})))
      fail(3, "%s: INCR burst at 0x%" PRIx64 " (%u x %u bytes) crosses a 4 KiB boundary", name_,
           addr, beats, 1u << ar.size);
    if (ar.burst == 2 && (beats != 2 && beats != 4 && beats != 8 && beats != 16))
      fail(3, "%s: WRAP burst of %u beats", name_, beats);
    if (ar.burst == 2 && (addr & ((1u << ar.size) - 1)))
      fail(3, "%s: unaligned WRAP burst at 0x%" PRIx64, name_, addr);
    const uint64_t ready = now + rng.range(lat_min_, lat_max_);
    q_[ar.id].push_back(Burst{addr, ready, seq_++, beats, ar.size, ar.burst, 0});
    ++pending_;
    ++st.bursts;
    if (pending_ > st.max_outstanding) st.max_outstanding = pending_;
  }

  // The R handshake of the presented beat.
  void taken() {
    Burst& b = q_[active_].front();
    ++st.beats;
    st.bytes += uint64_t{1} << b.size;
    if (beat_.resp == 2) ++st.slverr;
    if (beat_.resp == 3) ++st.decerr;
    beat_.valid = false;
    if (++b.beat == b.beats) {
      q_[active_].pop_front();
      --pending_;
      active_ = -1;
    }
  }

  const char* name_;
  uint64_t lo_, hi_;  // the memory's byte addresses [lo_, hi_)
  std::vector<uint8_t> mem_;
  std::vector<std::pair<uint64_t, uint64_t>> err_;
  uint32_t lat_min_, lat_max_;
  Coin gap_, stall_;
  std::deque<Burst> q_[Ids];
  uint64_t seq_ = 0, pending_ = 0;
  int active_ = -1;
  RBeat beat_;
  ArSignals ar_{};
  bool ar_wait_ = false;
};

// Drive a Verilator R channel from a beat (rvalid low when no beat is presented; the other R
// signals then keep their last values, as the original harness did).
template <unsigned DataBytes, typename Id, typename Data, typename Resp, typename Flag>
void drive_r(const RBeat& r, Id& rid, Data& rdata, Resp& rresp, Flag& rlast, Flag& rvalid) {
  rvalid = r.valid;
  if (!r.valid) return;
  set_bytes(rdata, r.data, DataBytes);
  rid = r.id;
  rresp = r.resp;
  rlast = r.last;
}

}  // namespace harness
