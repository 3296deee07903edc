# The two commands a new user runs: `make demo` and `make test`. Both install missing Debian
# packages (cluster/install-deps.sh), configure with a CMake preset and build.
#   make demo                 a 3-proxy PAN bank, a 3-ellipsoid modal bank and a 3-ground ground bank
#                             on 2 ranks (out/demo/), their summaries, and the demo scene rendered with
#                             PAN, modal and ground sound
#                             (out/demo/debris.wav, its stems and spectrogram); then the two simulated
#                             scenes of scenes/*.toml (clatter-sim: a rock slide and the plate
#                             pre-fractured), the intact plate's own modal model (clatter-bank object),
#                             the plate rendered with every source (out/demo/plate.wav), and 003's
#                             ceramic tile broken by its stress (docs/fracture.md; out/demo/tile.wav)
#   make test                 every test (ctest) but those labelled extended, in build/$(PRESET), then `make fuzz` at 10 s each
#   make test-extended        the extended tests (minutes each: the ground sound's elevation and eta sweep)
#   make fuzz                 the libFuzzer harnesses of the readers, 30 s each (preset fuzz, clang-14)
#   make bench                Google Benchmark suite, JSON in out/bench/
#   make PRESET=asan test     the same with ASan+UBSan (presets: release debug asan ci; fuzz: make fuzz)
PRESET ?= release
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc)
# OpenMPI refuses to run as root without these; harmless otherwise.
export OMPI_ALLOW_RUN_AS_ROOT := 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM := 1
export OMP_NUM_THREADS := 1
MAKEFLAGS += --no-print-directory
# The python3 with h5py that CMake chose (read when a recipe runs, i.e. after configuring).
PYTHON = $(shell sed -n 's/^CLATTER_PYTHON:FILEPATH=//p' $(BUILD)/CMakeCache.txt)

FUZZ_BUILD := build/fuzz
# Seconds each harness fuzzes after its corpus: 30 for `make fuzz`, 10 within `make test`.
FUZZ_SECONDS ?= 30
# make demo's plate bank: configs/modal-plate.toml (one entry like the typical piece; the tests'
# fixture) plus two entries like the scene's thinnest (a:b:c = 0.073:0.608:1) and longest
# (0.078:0.321:1) pieces, the patch down to a/c = 0.05, and every mode to 20 kHz for pieces up to
# 0.2 m (k = 4.9; the scene's lowest piece, 4.2 kHz, needs 4.7): ~50 s on 2 ranks, and every piece
# of the plate gets its whole band (docs/synth.md "Coverage").
PLATE_BANK := --set modes.largest_piece_m=0.2 --set patch.min_ratio=0.05 --set 'patch.samples=[\
  [0.10835590983317901, 0.5417795491658951, 0.8335069987167616], \
  [0.0622547676427212, 0.5185054620106094, 0.8528050362016604], \
  [0.07406352112697982, 0.3047998754071862, 0.949532322140767]]'

.PHONY: all deps build demo test test-extended fuzz bench clean
all: build

deps:
	@cluster/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake --preset $(PRESET)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j$(JOBS)

demo: build
	mpiexec -n 2 $(BUILD)/bin/clatter-bank pan -c configs/pan-demo.toml -o out/demo/bank.h5 --log-view
	$(BUILD)/bin/clatter-bank info out/demo/bank.h5
	mpiexec -n 2 $(BUILD)/bin/clatter-bank modal -c configs/modal-demo.toml -o out/demo/modal.h5 --log-view
	$(BUILD)/bin/clatter-bank info out/demo/modal.h5
	$(BUILD)/bin/clatter-bank probe out/demo/modal.h5 --entry 0 --point 1,2,2 | head -6
	mpiexec -n 2 $(BUILD)/bin/clatter-bank ground -c configs/ground-demo.toml -o out/demo/ground.h5 --log-view
	$(BUILD)/bin/clatter-bank info out/demo/ground.h5
	$(BUILD)/bin/clatter-synth -i scenes/demo.json -b out/demo/bank.h5 -m out/demo/modal.h5 -g out/demo/ground.h5 -o out/demo/debris.wav --stems
	$(PYTHON) analysis/spectrogram.py out/demo/debris.wav
	$(BUILD)/bin/clatter-sim -c scenes/rockslide.toml -o out/demo/rockslide.json
	$(BUILD)/bin/clatter-sim -c scenes/plate.toml --set plate.pieces=40 -o out/demo/plate.json
	mpiexec -n 2 $(BUILD)/bin/clatter-bank modal -c configs/modal-plate.toml $(PLATE_BANK) -o out/demo/modal-plate.h5 --log-view
	mpiexec -n 2 $(BUILD)/bin/clatter-bank object -c configs/object-plate.toml -o out/demo/objects-plate.h5 --log-view
	$(BUILD)/bin/clatter-bank info out/demo/objects-plate.h5
	$(BUILD)/bin/clatter-synth -i out/demo/plate.json -b out/demo/bank.h5 -m out/demo/modal-plate.h5 -O out/demo/objects-plate.h5 -g out/demo/ground.h5 -o out/demo/plate.wav --stems
	$(PYTHON) analysis/spectrogram.py out/demo/plate.wav
	$(BUILD)/bin/clatter-sim -c scenes/tile.toml -o out/demo/tile.json
	$(BUILD)/bin/clatter-synth -i out/demo/tile.json -b out/demo/bank.h5 -m out/demo/modal-plate.h5 -g out/demo/ground.h5 -o out/demo/tile.wav --stems
	$(PYTHON) analysis/spectrogram.py out/demo/tile.wav

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS) --timeout 300 -LE extended
	@$(MAKE) fuzz FUZZ_SECONDS=10

test-extended: build
	ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS) -L extended

$(FUZZ_BUILD)/CMakeCache.txt: | deps
	cmake --preset fuzz

# Only the harnesses and what they link (target fuzzers); each fuzzes its corpus for 30 s.
fuzz: deps $(FUZZ_BUILD)/CMakeCache.txt
	cmake --build $(FUZZ_BUILD) --target fuzzers -j$(JOBS)
	CLATTER_FUZZ_SECONDS=$(FUZZ_SECONDS) ctest --test-dir $(FUZZ_BUILD) -L fuzz --output-on-failure -j$(JOBS)

bench: build
	mkdir -p out/bench
	$(BUILD)/bin/clatter-bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
	    --benchmark_out=out/bench/bench.json --benchmark_out_format=json
	bench/fdtd.sh $(BUILD) 3 | tee out/bench/fdtd.txt
	test -f out/bench/pan.h5 || mpiexec -n 2 $(BUILD)/bin/clatter-bank pan -c configs/pan-demo.toml --set 'proxies.list_m=[]' -o out/bench/pan.h5
	$(BUILD)/bin/clatter-synth-bench out/bench/pan.h5 5 | tee out/bench/synth.txt
	test -f out/bench/modal.h5 || mpiexec -n 2 $(BUILD)/bin/clatter-bank modal -c configs/modal-demo.toml -o out/bench/modal.h5
	$(BUILD)/bin/clatter-synth-bench out/bench/pan.h5 5 210741 out/bench/modal.h5 | tee out/bench/synth-modal.txt
	test -f out/bench/ground.h5 || mpiexec -n 2 $(BUILD)/bin/clatter-bank ground -c configs/ground-demo.toml -o out/bench/ground.h5
	$(BUILD)/bin/clatter-synth-bench out/bench/pan.h5 5 210741 out/bench/modal.h5 out/bench/ground.h5 | tee out/bench/synth-ground.txt
	$(BUILD)/bin/clatter-synth-table-bench out/bench/modal.h5 5 | tee out/bench/synth-table.txt

clean:
	rm -rf build out
