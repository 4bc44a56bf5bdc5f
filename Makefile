# carbonmesh: two commands. `make run` builds and runs the main job on a built-in shape; `make test` runs all tests.
BUILD ?= build
JOBS  ?= $(shell nproc)
OUT   ?= out

.PHONY: all bootstrap build run test clean

all: build

bootstrap:
	./scripts/bootstrap

build: bootstrap
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

CLI = $(BUILD)/tools/carbonmesh/carbonmesh

# The main job on the built-in default shape.
run: build
	mkdir -p $(OUT)
	$(CLI) shape sphere --radius 10 --subdivisions 3 -o $(OUT)/sphere.off
	$(CLI) stats $(OUT)/sphere.off

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD)
