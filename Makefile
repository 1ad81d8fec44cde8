# Hermite Lab — the two commands of the README:
#   make run    install missing Debian packages, build Release, run the program's main job
#   make test   the same set-up, then build and run the whole test suite through ctest
# Both are idempotent: when nothing changed they only check packages and let Ninja find nothing to do.

BUILD_DIR   ?= build/release
ASAN_DIR    ?= build/asan
CMAKE_FLAGS ?=
JOBS        ?= $(shell nproc)

.PHONY: run test setup configure build test-sanitize bench clean

setup:
	@./scripts/install-deps.sh

configure: setup
	@mkdir -p build
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS) > $(BUILD_DIR).configure.log 2>&1 \
	  || { mkdir -p build; cat $(BUILD_DIR).configure.log; exit 1; }

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	@./$(BUILD_DIR)/hermite-lab $(ARGS)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure --timeout 900 -j $(JOBS)

# ASan + UBSan build of core (math, loaders, scene files) and its tests, without the label slow
# (docs/design.md, Testing).
test-sanitize: setup
	@mkdir -p build
	@cmake -S . -B $(ASAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHERMITE_SANITIZE=ON \
	  -DHERMITE_NATIVE=OFF $(CMAKE_FLAGS) > $(ASAN_DIR).configure.log 2>&1 || { cat $(ASAN_DIR).configure.log; exit 1; }
	@cmake --build $(ASAN_DIR) -j $(JOBS) --target hermite_core_tests
	@cd $(ASAN_DIR) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --output-on-failure --timeout 900 -j $(JOBS) -L core -LE slow

bench: build
	@./$(BUILD_DIR)/hermite-lab bench $(ARGS)

clean:
	rm -rf build
