# carbonmesh: two commands. `make run` builds and runs the main job on a built-in shape; `make test` runs all tests.
BUILD ?= build
JOBS  ?= $(shell nproc)
OUT   ?= out

.PHONY: all bootstrap build run test test-asan fuzz clean

all: build

bootstrap:
	./scripts/bootstrap

build: bootstrap
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

CLI = $(BUILD)/tools/carbonmesh/carbonmesh

# The main job on the built-in default shape: remesh, dual, optimise, LAMMPS/REBO2 files and the defect report.
run: build
	$(CLI) build -o $(OUT)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The whole suite under AddressSanitizer + UndefinedBehaviorSanitizer.
test-asan: bootstrap
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCARBONMESH_SANITIZE=ON
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS)

# libFuzzer targets (clang), each run for FUZZ_SECONDS.
FUZZ_SECONDS ?= 60
fuzz: bootstrap
	CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCARBONMESH_FUZZ=ON \
	  -DCARBONMESH_BUILD_TESTS=OFF
	cmake --build build-fuzz -j $(JOBS) --target fuzz_targets
	tests/fuzz/run.sh build-fuzz $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD)
