# BxDF Lab: `make test` and `make report` do everything on a fresh Debian machine
# (install missing packages, configure, build, then test or report).
BUILD  ?= build
JOBS   ?= $(shell nproc)
PYTHON := /usr/bin/python3
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: all deps configure build test test-cpp test-python test-blender test-compare report bench clean install-addon addon-zip compare fuzz test-sanitize

all: build

deps:
	@bash tools/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) $(CMAKE_FLAGS) -DPython_EXECUTABLE=$(PYTHON) > $(BUILD).configure.log 2>&1 \
	  || (cat $(BUILD).configure.log; exit 1)

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

test: build
	@bash tools/run-tests.sh $(BUILD)

# One suite at a time (make test runs them all).
test-cpp test-python test-blender test-compare: build
	@bash tools/run-tests.sh $(BUILD) $(patsubst test-%,%,$@)

report: build
	@$(BUILD)/core/bxdf-rho-table
	@BXDF_PYTHONPATH=$(CURDIR)/$(BUILD)/python $(PYTHON) -m compare run

install-addon: build
	@bash tools/install-addon.sh $(BUILD)

# Your own scene through BXDF_LAB, Cycles and POV-Ray: make compare BLEND=scene.blend
compare: build
	@test -n "$(BLEND)" || { echo "usage: make compare BLEND=FILE.blend"; exit 2; }
	@BXDF_PYTHONPATH=$(CURDIR)/$(BUILD)/python $(PYTHON) -m compare run --blend "$(BLEND)"

# $(BUILD)/bxdf_lab-<version>.zip: the add-on with the compiled module, for Preferences > Add-ons > Install.
addon-zip: build
	@bash tools/addon-zip.sh $(BUILD)

bench: build
	@bash tools/run-bench.sh $(BUILD)

# libFuzzer targets under ASan + UBSan, built with clang in their own folder; each runs for
# FUZZ_SECONDS (make fuzz FUZZ_SECONDS=600) and any finding fails the target.
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 120
FUZZ_TARGETS ?= scene_json material_json cornell merl
fuzz: deps
	@CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBXDF_FUZZ=ON \
	  -DBXDF_WERROR=OFF -DBXDF_BUILD_TESTS=OFF -DBXDF_BUILD_BENCH=OFF -DBXDF_BUILD_PYTHON=OFF \
	  > $(FUZZ_BUILD).configure.log 2>&1 || (cat $(FUZZ_BUILD).configure.log; exit 1)
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	@bash tools/run-fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# ctest and pytest with every library and the Python module under ASan + UBSan
# (-fno-sanitize-recover: the first report fails the test), in its own build folder.
SANITIZE_BUILD ?= build-sanitize
# -O1 -g1: ASan's own advice, and it roughly halves the build on two cores against -O2 -g.
test-sanitize: deps
	@cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBXDF_SANITIZE=ON \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" \
	  -DBXDF_WERROR=OFF -DBXDF_BUILD_BENCH=OFF -DPython_EXECUTABLE=$(PYTHON) \
	  > $(SANITIZE_BUILD).configure.log 2>&1 || (cat $(SANITIZE_BUILD).configure.log; exit 1)
	@cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	@bash tools/run-sanitized-tests.sh $(SANITIZE_BUILD)

clean:
	rm -rf $(BUILD) $(BUILD).configure.log
