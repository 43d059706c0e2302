# Fenestra: `make demo`, `make test`, `make bench`. Everything runs with Debian's /usr/bin/python3.
PYTHON := /usr/bin/python3
BUILD  := build
JOBS   ?= $(shell nproc)

.PHONY: deps build test cpp-test py-test demo bench install clean

deps:
	@./scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=$(PYTHON) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

cpp-test: build
	$(BUILD)/cpp_tests/fenestra_tests

py-test: build
	cd python_tests && $(PYTHON) -m pytest -q

test: cpp-test py-test

demo: build
	@./scripts/demo.sh $(BUILD)

bench: build
	$(BUILD)/bench/fenestra_sky_bench
	$(BUILD)/bench/fenestra_bench

# Puts `fenestra` on PATH and makes `import fenestra` work in /usr/bin/python3 (this checkout's addon/).
SITE := $(shell $(PYTHON) -c "import site; print(site.getsitepackages()[0])")
install: build
	ln -sf $(CURDIR)/$(BUILD)/fenestra /usr/local/bin/fenestra
	mkdir -p $(SITE)
	echo "$(CURDIR)/addon" > $(SITE)/fenestra.pth
	@echo "installed: /usr/local/bin/fenestra and $(SITE)/fenestra.pth -> $(CURDIR)/addon"

clean:
	rm -rf $(BUILD)
