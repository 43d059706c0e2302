# Fenestra: `make demo`, `make test`, `make bench`. Everything runs with Debian's /usr/bin/python3, but for
# packaging (`make wheel`, `make extension`), whose PyPI tools live in a venv of pyenv's Python 3.11, and
# the headless Blender suite's second Blender, bpy 4.5, in its own venv (bpy-venv).
PYTHON := /usr/bin/python3
BUILD  := build
JOBS   ?= $(shell nproc)

.PHONY: deps build bpy-venv test layers cpp-test py-test wheel extension demo demo-annual bench validate install install-addon examples-blend clean

deps:
	@./scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=$(PYTHON) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

cpp-test: build
	$(BUILD)/cpp_tests/fenestra_tests

# Blender 4.5 LTS as the bpy module (requirements/bpy.txt), for the headless add-on suite: a venv
# of the `python3` first on PATH (a Python 3.11 that is not Debian's; BPY_PYTHON to choose another).
BPY_VENV := $(BUILD)/bpy-venv
bpy-venv:
	@./scripts/bpy-venv.sh $(BPY_VENV)

# The Blender suites run in Debian's Blender 3.4 and in bpy 4.5 (python_tests/blenders.py), bpy 4.5's
# with the add-on installed from the extension zip; the suite installs the wheel too (test_wheel.py,
# test_extension.py).
py-test: build extension bpy-venv
	cd python_tests && FENESTRA_BPY_PYTHON=$(CURDIR)/$(BPY_VENV)/bin/python $(PYTHON) -m pytest -q

# Each layer of the native core includes only layers below it (docs/architecture.md).
layers:
	$(PYTHON) scripts/check_layers.py

test: layers cpp-test py-test

# The wheel (pyproject.toml) and the Blender 4.2+ extension, in $(DIST) (docs/install.md). PyPI's
# packaging tools (requirements/packaging.txt) live in a venv of pyenv's Python 3.11, never Debian's.
# PACKAGING_PYTHON=/path/to/python3.13 PACKAGING_VENV=build/venv/packaging-cp313 makes a cp313 wheel.
DIST           := $(BUILD)/dist
PACKAGING_VENV ?= $(BUILD)/venv/packaging
wheel: build
	@py=$$(FENESTRA_PACKAGING_PYTHON=$(PACKAGING_PYTHON) ./scripts/packaging-venv.sh $(PACKAGING_VENV)) && \
	  JOBS=$(JOBS) ./scripts/build_wheel.sh "$$py" $(BUILD) $(DIST) >$(BUILD)/wheel-path.txt && \
	  echo "wheel: $$(cat $(BUILD)/wheel-path.txt)"

extension: wheel
	@echo "extension: $$($(PYTHON) scripts/make_extension.py $$(cat $(BUILD)/wheel-path.txt) $(DIST))"

# The reference room against Radiance, then the apartment example solved and rendered in Blender.
demo: build install-addon
	@if ! $(PYTHON) -c "import matplotlib" 2>/dev/null && command -v apt-get >/dev/null && [ "$$(id -u)" = 0 ]; then \
	  echo "installing python3-matplotlib (the demo's goal / achieved image)"; \
	  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends python3-matplotlib >/dev/null; fi
	@./scripts/demo.sh $(BUILD)

# An annual design: examples/annual_room/design.json (sDA300/50% >= 55 %, ASE1000,250 <= 10 %, the least
# glazing, Chicago weather) solved headless; docs/annual-design.png and out/annual_design/result.json.
demo-annual: build
	@if ! $(PYTHON) -c "import matplotlib" 2>/dev/null && command -v apt-get >/dev/null && [ "$$(id -u)" = 0 ]; then \
	  echo "installing python3-matplotlib (the demo's picture)"; \
	  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends python3-matplotlib >/dev/null; fi
	$(PYTHON) scripts/annual_design_demo.py examples/annual_room/design.json docs/annual-design.png out/annual_design/result.json

bench: build
	$(BUILD)/bench/fenestra_sky_bench
	$(BUILD)/bench/fenestra_solver_bench
	$(BUILD)/bench/fenestra_bench
	$(BUILD)/bench/fenestra_annual_metrics_bench
	$(BUILD)/bench/fenestra_annual_bench
	$(BUILD)/bench/fenestra_climate_design_bench
	$(PYTHON) scripts/forward_check_bench.py $(BUILD)/fenestra
	$(PYTHON) scripts/distributed_bench.py
	$(PYTHON) scripts/floor_bench.py

# Ground truth: known openings' light as goals, solved for and checked (out/validate/, README table).
validate: build examples-blend
	$(PYTHON) scripts/validate.py

# Puts `fenestra` on PATH and makes `import fenestra` work in /usr/bin/python3 (this checkout's addon/).
SITE := $(shell $(PYTHON) -c "import site; print(site.getsitepackages()[0])")
install: build
	ln -sf $(CURDIR)/$(BUILD)/fenestra /usr/local/bin/fenestra
	mkdir -p $(SITE)
	echo "$(CURDIR)/addon" > $(SITE)/fenestra.pth
	@echo "installed: /usr/local/bin/fenestra and $(SITE)/fenestra.pth -> $(CURDIR)/addon"

# Links addon/fenestra (with its native module) into Blender's user add-ons and enables it.
BLENDER ?= blender
install-addon: build
	@if ! command -v $(BLENDER) >/dev/null; then echo "install-addon: Blender not found, skipped"; exit 0; fi; \
	dir=$$($(BLENDER) -b --factory-startup --python-expr "import bpy; print('ADDONS=' + bpy.utils.user_resource('SCRIPTS', path='addons'))" 2>/dev/null | sed -n 's/^ADDONS=//p'); \
	test -n "$$dir" || { echo "install-addon: could not ask Blender for its add-on folder"; exit 1; }; \
	mkdir -p "$$dir"; \
	if [ -e "$$dir/fenestra" ] && [ ! -L "$$dir/fenestra" ]; then echo "install-addon: $$dir/fenestra exists and is not a link: remove it first"; exit 1; fi; \
	ln -sfn $(CURDIR)/addon/fenestra "$$dir/fenestra"; \
	$(BLENDER) -b --python-exit-code 1 --python-expr "import bpy; bpy.ops.preferences.addon_enable(module='fenestra'); bpy.ops.wm.save_userpref()" >/dev/null && \
	echo "installed and enabled: $$dir/fenestra -> $(CURDIR)/addon/fenestra (3D View > Sidebar > Fenestra)"

# The Blender examples (examples/build_blend_examples.py): room, apartment, museum, thick_walls as
# out/examples/NAME.blend; their study folders (scene.json + scene.obj) in examples/NAME_study/,
# the museum's (6.5 MB of OBJ) in out/examples/museum_study/.
examples-blend: build
	$(BLENDER) -b --factory-startup --python-exit-code 1 --python examples/build_blend_examples.py -- out/examples --studies examples

clean:
	rm -rf $(BUILD)
