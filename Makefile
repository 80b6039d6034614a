# Set-up and everyday commands. `make run` and `make test` work on a fresh Debian 12 machine as root
# (they install the missing packages first).
BUILD ?= build
ASAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)
SCENE ?= scenes/default.json
GENERATOR := $(shell command -v ninja >/dev/null 2>&1 && echo "-G Ninja")

.PHONY: all deps configure build run test sanitize bench gallery install clean

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=Release

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build $(BUILD) -j $(JOBS)

## Renders the default scene to out/default.png and prints size, BVH build time, render time, Mrays/s.
run: configure
	cmake --build $(BUILD) -j $(JOBS) --target wideray
	$(BUILD)/wideray render $(SCENE) -o out/default.png

## Builds and runs every test through ctest.
test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

## The test suite built with AddressSanitizer and UndefinedBehaviorSanitizer.
sanitize: deps
	cmake -S . -B $(ASAN_BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWIDERAY_SANITIZE=ON -DWIDERAY_BENCHMARKS=OFF
	cmake --build $(ASAN_BUILD) -j $(JOBS) --target wideray_tests wideray
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

install: build
	cmake --install $(BUILD)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) out
