# The front door. `make render` and `make test` are the README's two commands: each installs what
# is missing, configures, builds Release, then renders or tests. Idempotent; seconds when nothing changed.
BUILD      ?= build
# The sanitizer build runs each suite as this many ctest entries (tests/CMakeLists.txt, SVBRDF_TEST_SHARDS).
ASAN_SHARDS ?= 6
ASAN_BUILD ?= build-asan
FUZZ_BUILD ?= build-fuzz
JOBS       ?= $(shell nproc)
PREFIX     ?= /usr/local
CTEST_ARGS ?=
LAUNCHER   := $(if $(shell command -v ccache),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache,)
# ccache keys on paths relative to the checkout, so a second clone (CI's) reuses what this one built.
export CCACHE_BASEDIR ?= $(CURDIR)
export CCACHE_NOHASHDIR ?= 1

.PHONY: all deps configure build install test test-long render bench asan asan-contract fuzz fuzz-smoke format lod-report clean

all: build

deps:
	@tools/install-deps

$(BUILD)/build.ninja:
	@$(MAKE) --no-print-directory deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release $(LAUNCHER)

configure: deps $(BUILD)/build.ninja

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The libraries, their public headers, the programs and the CMake package under PREFIX
# (docs/library.md), e.g. `make install PREFIX=~/.local`.
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# Runs every test but the heavy ones labelled `long` (`make test-long` runs those). CI passes
# OPTIMIZED_ONLY=1: in Release it runs only the tests of the labels below — the comparisons that need an
# optimized build, and the Python module's, which the sanitizer build leaves out (an instrumented module
# needs its runtime preloaded into the interpreter), and the farm test on a one-node Slurm cluster
# (label slurm: its daemons and tasks in Release, not its assertions, are what it exercises) — and every
# other suite under the sanitizers (`make asan`), which assert the same and more.
OPTIMIZED_LABELS := ^lod$$|^blender$$|-optimized$$|^python$$|^slurm$$
test: build
	cd $(BUILD) && ctest -j $(JOBS) --output-on-failure --timeout 600 -LE long \
	  $(if $(OPTIMIZED_ONLY),-L '$(OPTIMIZED_LABELS)',) $(CTEST_ARGS)

test-long: build
	cd $(BUILD) && ctest -j $(JOBS) --output-on-failure --timeout 1800 -L long $(CTEST_ARGS)

render: build
	@mkdir -p out
	$(BUILD)/svbrdf-render --out out/showcase.exr

bench: build
	@for b in $(BUILD)/bench/*/bench_*; do echo "== $$b"; $$b --benchmark_repetitions=5 --benchmark_report_aggregates_only=true; done

# The distance-LOD report at its full size (4096 samples per pixel; long: about 80 minutes
# on 2 cores, 54 with only --filter param --filter brdf): out/lod-report/index.html.
lod-report: build
	$(BUILD)/svbrdf-lod-report --full --out out/lod-report

$(ASAN_BUILD)/build.ninja:
	@$(MAKE) --no-print-directory deps
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" -DSVBRDF_SANITIZE=ON -DSVBRDF_BUILD_BENCH=OFF \
	  -DSVBRDF_TEST_SHARDS=$(ASAN_SHARDS) $(LAUNCHER)

# Tests under AddressSanitizer + UndefinedBehaviorSanitizer: every suite but the `long` runs and the
# comparisons that need an optimized build (OPTIMIZED_LABELS: the LOD renders, the Blender renders, the
# pyramid's bars), which stay in the Release runs; under the sanitizers they alone would exceed CI's
# budget. CI runs this on every run; UndefinedBehaviorSanitizer's findings fail the test.
asan: deps $(ASAN_BUILD)/build.ninja
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest -j $(JOBS) --output-on-failure --timeout 900 -LE 'long|$(OPTIMIZED_LABELS)' $(CTEST_ARGS)

# The programs' contract with their input and output under the sanitizers, in about two minutes of
# tests (a quick check while working on the readers; `make asan` runs these and every other suite):
# hostile and corrupt files, resource limits, output writes, interrupts and command lines.
CONTRACT_TESTS := HostileInput.*:GltfConformance.*:GltfVertexData.*:JsonScan.*:CorruptInput.*:OutputContract.*:OutputLocation.*:AtomicFile.*:TempFileRegistry.*:Interrupt.*:CliBounds.*:BakeContract.*:BakeCli.*:Image.*:MipFile.*:FilterTaps.*
# Only the suites that hold these tests (and the programs they run) are built: the appearance and
# LOD suites, the report and the plots are not needed here (about a sixth of the sanitizer build). The
# suites run as GoogleTest runs them, filtered to these tests: the sanitizer build's ctest entries are
# shards of whole suites.
asan-contract: deps $(ASAN_BUILD)/build.ninja
	cmake --build $(ASAN_BUILD) -j $(JOBS) --target render_tests mip_tests textures_tests
	cd $(ASAN_BUILD) && for suite in render mip textures; do \
	  SVBRDF_MIP_CACHE=$(abspath $(ASAN_BUILD))/tests/mip-cache ASAN_OPTIONS=detect_leaks=0 \
	    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 tests/$$suite/$${suite}_tests --gtest_brief=1 \
	    --gtest_filter='$(CONTRACT_TESTS)' || exit 1; done

# The libFuzzer targets of fuzz/ (fuzz/README.md), built by clang with AddressSanitizer and
# UndefinedBehaviorSanitizer: only the libraries they read through, not the programs or the suites.
$(FUZZ_BUILD)/build.ninja:
	@$(MAKE) --no-print-directory deps
	cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_COMPILER=clang++-14 \
	  -DCMAKE_CXX_FLAGS="-O1 -g1" -DSVBRDF_SANITIZE=ON -DSVBRDF_FUZZ=ON -DSVBRDF_BUILD_TESTS=OFF \
	  -DSVBRDF_BUILD_BENCH=OFF $(LAUNCHER)

fuzz: deps $(FUZZ_BUILD)/build.ninja
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_targets

# Every target on its corpus and its regression inputs, then a short mutation run of each (CI's check,
# about a minute and a half); fails on any finding.
fuzz-smoke: fuzz
	fuzz/smoke $(FUZZ_BUILD)/fuzz

format:
	@git ls-files '*.h' '*.cpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD) out
