# Set-up and everyday commands. `make run` and `make test` work on a fresh Debian 12 machine as root
# (they install the missing packages first).
BUILD ?= build
ASAN_BUILD ?= build-asan
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 180
JOBS ?= $(shell nproc)
SCENE ?= scenes/default.json
GENERATOR := $(shell command -v ninja >/dev/null 2>&1 && echo "-G Ninja")

.PHONY: all deps configure build run test sanitize fuzz bench bench-accelerators gallery install clean

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
	cmake --build $(ASAN_BUILD) -j $(JOBS) --target wideray_tests wideray_api_tests wideray image_equal
	ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp UBSAN_OPTIONS=print_stacktrace=1 ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

## Every libFuzzer harness (fuzz/) for FUZZ_SECONDS each (or runs:N inputs from a fixed seed), built with clang, ASan and UBSan; crashes
## and the corpus go to out/fuzz/ (scripts/fuzz.sh, docs/robustness.md)
fuzz: deps
	@scripts/install-deps.sh clang-14 libclang-rt-14-dev
	CC=clang-14 CXX=clang++-14 cmake -S . -B $(FUZZ_BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWIDERAY_FUZZ=ON -DWIDERAY_TESTS=OFF -DWIDERAY_BENCHMARKS=OFF
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzzers
	ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp UBSAN_OPTIONS=print_stacktrace=1 scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

## Our kernels (on our fast and high quality builds, 8 and 16 children per node) against Embree's (on
## its medium and high quality builds) on the shared meshes, framed
## from outside, and on interior views (BENCH_SCENES): a comparison on all threads (out/bench.json),
## a thread-scaling run on 1..nproc threads (out/scaling.json), then docs/performance.md and
## docs/performance.svg regenerated from the JSON. Meshes missing from SCENES_DIR are left out.
SCENES_DIR ?= ../shared/scenes
BENCH_SIZE ?= 1024x1024
BENCH_RUNS ?= 5
BENCH_MESHES ?= cornell-box/CornellBox-Original.obj suzanne/suzanne.obj teapot/teapot.obj \
  stanford-bunny/bun_zipper.ply stanford-dragon-100k/dragon_100k.ply \
  bitterli-coffee-maker/coffee_maker_merged.ply crytek-sponza/sponza.obj \
  bitterli-country-kitchen/country_kitchen_merged.ply
# Interior views: scene files with their own cameras inside the shared meshes (they name ../shared).
BENCH_SCENES ?= scenes/sponza_interior.json scenes/country_kitchen.json
SCALING_MESHES ?= stanford-bunny/bun_zipper.ply crytek-sponza/sponza.obj
SCALING_THREADS ?= $(shell seq 1 $(shell nproc))
BENCH_COMMAND = $(BUILD)/wideray bench $(wildcard $(addprefix $(SCENES_DIR)/,$(BENCH_MESHES))) $(BENCH_SCENES) \
  --size $(BENCH_SIZE) --runs $(BENCH_RUNS) --quality both --accel bvh16 --counters --json out/bench.json
SCALING_COMMAND = $(BUILD)/wideray bench $(wildcard $(addprefix $(SCENES_DIR)/,$(SCALING_MESHES))) \
  --size $(BENCH_SIZE) --runs $(BENCH_RUNS) --rays primary,diffuse
SCALING_LOOP = for t in $(SCALING_THREADS); do $(SCALING_COMMAND) --threads $$t --json out/scaling-$$t-threads.json || exit 1; done
SCALING_MERGE = python3 scripts/performance_report.py merge out/scaling.json $(foreach t,$(SCALING_THREADS),out/scaling-$(t)-threads.json)

# The acceleration structures side by side (docs/accelerators.md): our single-ray kernels over every
# structure of --accel, on the same meshes and interiors and on the teapot in a stadium.
ACCEL_SIZE ?= 512x512
ACCEL_SCENES ?= $(BENCH_SCENES) scenes/teapot_stadium.json
ACCEL_COMMAND = $(BUILD)/wideray bench $(wildcard $(addprefix $(SCENES_DIR)/,$(BENCH_MESHES))) $(ACCEL_SCENES) \
  --size $(ACCEL_SIZE) --runs 3 --backend wideray --rays primary,shadow,diffuse \
  --accel bvh4,bvh2,skip,kdtree,grid,hgrid,rgrid --counters --json out/accelerators.json

bench: deps
	@test -d $(SCENES_DIR) || { echo "make bench needs the shared meshes in $(SCENES_DIR) (set SCENES_DIR)" >&2; exit 1; }
	cmake -S . -B $(BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS) --target wideray
	$(BENCH_COMMAND)
	$(SCALING_LOOP)
	$(SCALING_MERGE)
	python3 scripts/performance_report.py report --bench out/bench.json --scaling out/scaling.json \
	  --command '$(BENCH_COMMAND)' --command '$(SCALING_LOOP)' --command '$(SCALING_MERGE)' \
	  --markdown docs/performance.md --chart docs/performance.svg
	$(MAKE) --no-print-directory bench-accelerators

## The acceleration structures alone (part of make bench): out/accelerators.json, docs/accelerators.md.
bench-accelerators: deps
	@test -d $(SCENES_DIR) || { echo "make bench-accelerators needs the shared meshes in $(SCENES_DIR) (set SCENES_DIR)" >&2; exit 1; }
	cmake -S . -B $(BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS) --target wideray
	$(ACCEL_COMMAND)
	python3 scripts/accelerators_report.py --bench out/accelerators.json --command '$(ACCEL_COMMAND)' \
	  --why docs/accelerators-why.md --markdown docs/accelerators.md

## Renders every effect scene to docs/gallery/NAME.png.
GALLERY_SCENES := beer metals soft_shadows glossy dof textures fog polarization polarization_off quadrics blobs terrain csg motion_blur
# The path-traced interior needs the shared Sponza.
GALLERY_SCENES += $(if $(wildcard $(SCENES_DIR)/crytek-sponza/sponza.obj),sponza_path)
GALLERY_SCENES += $(if $(wildcard $(SCENES_DIR)/stanford-bunny/bun_zipper.ply),bunny_field)
# The Bitterli scenes from their own pbrt files (docs/scene-format.md, "pbrt scene files"), when present.
GALLERY_PBRT := $(if $(wildcard $(SCENES_DIR)/bitterli-country-kitchen/scene.pbrt),bitterli-country-kitchen:640x360) \
  $(if $(wildcard $(SCENES_DIR)/bitterli-coffee-maker/scene.pbrt),bitterli-coffee-maker:400x500)
gallery: configure
	cmake --build $(BUILD) -j $(JOBS) --target wideray
	mkdir -p docs/gallery
	$(BUILD)/wideray render $(GALLERY_SCENES:%=scenes/%.json) -o docs/gallery/
	for entry in $(GALLERY_PBRT); do scene=$${entry%%:*}; \
	  $(BUILD)/wideray render $(SCENES_DIR)/$$scene/scene.pbrt --size $${entry##*:} --spp 64 -o docs/gallery/$$scene.png || exit 1; done

install: build
	cmake --install $(BUILD)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) out
