# tinlod: `make demo` and `make test` set up, build and run on a fresh Debian 12 machine.
BUILD ?= build
JOBS ?= $(shell nproc)
SANITIZE ?=
CMAKE_FLAGS ?=
ifneq ($(SANITIZE),)
BUILD := build-sanitize
CMAKE_FLAGS += -DTINLOD_SANITIZE=$(SANITIZE)
BUILD_TYPE ?= RelWithDebInfo
endif
BUILD_TYPE ?= Release

.PHONY: setup configure build demo test bench clean

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

clean:
	rm -rf build build-sanitize
