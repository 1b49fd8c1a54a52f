# Entry points for people and CI. `make demo` and `make test` work on a fresh Debian 12 machine.
BUILD ?= build
ASAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)
DEMO_OUT ?= out/demo.png

.PHONY: deps configure build demo test asan-configure test-asan fuzz format clean

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p $(dir $(DEMO_OUT))
	@$(BUILD)/app/diffphoton render resources/sample/sample.json -o $(DEMO_OUT:.png=.exr) --layers
	@$(BUILD)/app/diffphoton convert $(DEMO_OUT:.png=.exr) $(DEMO_OUT) --exposure -2
	@echo "demo: wrote $(abspath $(DEMO_OUT:.png=.exr)) (linear RGBA, layers objects/catcher/dL/alpha/shadow) and $(abspath $(DEMO_OUT))"

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Unit and command-line tests under AddressSanitizer + UndefinedBehaviorSanitizer (the slow
# statistical render suite runs in `make test` only). The sanitizer build is clang's, with
# coverage instrumentation, so the same build also holds the libFuzzer targets.
UNIT_TESTS = $(patsubst tests/unit/%/,test_%,$(sort $(dir $(wildcard tests/unit/*/*.cpp))))
FUZZ_TARGETS = project fspy image mesh scene merge cli mesh_files
FUZZ_EXES = $(addprefix fuzz_,$(FUZZ_TARGETS))
asan-configure: deps
	@cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
	  -DCMAKE_CXX_COMPILER=clang++ -DDP_SANITIZE=ON -DDP_FUZZ=ON -DDP_BUILD_BENCH=OFF -DDP_BUILD_UI=OFF > /dev/null

test-asan: asan-configure
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target $(UNIT_TESTS) $(FUZZ_EXES) diffphoton
	@cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/fuzz/lsan.supp \
	  ctest --output-on-failure -j $(JOBS) -L 'unit|cli'

# Each fuzz target for FUZZ_SECONDS (tests/fuzz/README.md). New inputs collect in out/fuzz/corpus;
# a finding is written to out/fuzz/findings/<target>/ and fails the run. A small input costing
# more than 5 s, 1 GB resident or one allocation over 512 MB is a finding too.
FUZZ_SECONDS ?= 60
FUZZ_FLAGS ?= -rss_limit_mb=1024 -malloc_limit_mb=512 -timeout=5
fuzz: asan-configure
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target $(FUZZ_EXES)
	@for t in $(FUZZ_TARGETS); do \
	  mkdir -p out/fuzz/corpus/$$t out/fuzz/findings/$$t; \
	  echo "fuzz: $$t for $(FUZZ_SECONDS) s"; \
	  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=tests/fuzz/lsan.supp \
	    $(ASAN_BUILD)/tests/fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) $(FUZZ_FLAGS) \
	    -artifact_prefix=out/fuzz/findings/$$t/ -print_final_stats=1 out/fuzz/corpus/$$t tests/fuzz/corpus/$$t \
	    > out/fuzz/$$t.log 2>&1 || { tail -40 out/fuzz/$$t.log; exit 1; }; \
	  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" out/fuzz/$$t.log | tr '\n' ' '; echo; \
	done

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) out
