# tinlod: `make demo` and `make test` set up, build and run on a fresh Debian 12 machine.
BUILD ?= build
JOBS ?= $(shell nproc)
SANITIZE ?=
CMAKE_FLAGS ?=
ifneq ($(SANITIZE),)
BUILD := build-sanitize
CMAKE_FLAGS += -DTINLOD_SANITIZE=$(SANITIZE)
BUILD_TYPE ?= RelWithDebInfo
export LSAN_OPTIONS = suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0
endif
BUILD_TYPE ?= Release

FUZZ_SECONDS ?= 60
FUZZ_RUNS ?= -1

.PHONY: setup configure build demo test bench fuzz format clean

setup:
	@./scripts/setup.sh

configure: setup
	@mkdir -p $(BUILD)
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_FLAGS) > $(BUILD)/configure.log 2>&1 \
		|| (cat $(BUILD)/configure.log; exit 1)

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@./scripts/demo.sh $(BUILD)/bin

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@./bench/run.sh $(BUILD)/bin $(ARGS)

# Each fuzz target runs FUZZ_SECONDS (or FUZZ_RUNS executions, if fewer), one after the other,
# seeded from the real files in meshes/; findings land in build-fuzz/findings/.
fuzz: setup
	@mkdir -p build-fuzz
	@CC=clang CXX=clang++ cmake -S . -B build-fuzz -DTINLOD_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
		> build-fuzz/configure.log 2>&1 || (cat build-fuzz/configure.log; exit 1)
	@cmake --build build-fuzz -j $(JOBS)
	@./scripts/fuzz.sh build-fuzz $(FUZZ_SECONDS) $(FUZZ_RUNS)

# Rewrites the C++ sources in the repository's clang-format style (`make test` checks it).
format:
	@./scripts/format.sh

clean:
	rm -rf build build-sanitize build-fuzz
