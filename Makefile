# Entry points for people and CI. `make demo` and `make test` work on a fresh Debian 12 machine.
BUILD ?= build
ASAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)
DEMO_OUT ?= out/demo.png

.PHONY: deps configure build demo test test-asan format clean

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
	@echo "demo: wrote $(abspath $(DEMO_OUT:.png=.exr)) (linear, layers dL/alpha/shadow) and $(abspath $(DEMO_OUT))"

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Unit and command-line tests under AddressSanitizer + UndefinedBehaviorSanitizer (the slow
# statistical render suite runs in `make test` only).
UNIT_TESTS = $(patsubst tests/unit/%/,test_%,$(sort $(dir $(wildcard tests/unit/*/*.cpp))))
test-asan: deps
	@cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DDP_SANITIZE=ON -DDP_BUILD_BENCH=OFF -DDP_BUILD_UI=OFF > /dev/null
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target $(UNIT_TESTS) diffphoton
	@cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -j $(JOBS) -L 'unit|cli'

format:
	@clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) out
