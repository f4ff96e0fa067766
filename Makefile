# BxDF Lab: `make test` and `make report` do everything on a fresh Debian machine
# (install missing packages, configure, build, then test or report).
BUILD  ?= build
JOBS   ?= $(shell nproc)
PYTHON := /usr/bin/python3
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: all deps configure build test test-cpp test-python test-blender test-compare report bench clean install-addon addon-zip compare

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

clean:
	rm -rf $(BUILD) $(BUILD).configure.log
