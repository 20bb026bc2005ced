# The README's two commands:
#   make demo   installs what is missing, builds, and runs limsurf on a bundled mesh
#   make test   installs what is missing, fuzzes each parser for 30 s, builds, and runs every test (CI runs this)
# Other targets: make asan (the whole suite under sanitizers), make fuzz, make install PREFIX=...

JOBS ?= 2
PREFIX ?= /usr/local
DEMO_MESH ?= data/meshes/cube_creases.obj
DEMO_OUT ?= out/demo

.PHONY: demo test asan fuzz install setup clean

setup:
	@bash scripts/setup.sh

demo: setup
	cmake --preset release >/dev/null
	cmake --build --preset release -j $(JOBS) --target limsurf_cli
	bash scripts/demo.sh build/release/cli/limsurf $(DEMO_MESH) $(DEMO_OUT)

test: setup
	bash fuzz/run.sh 30
	cmake --preset ci
	cmake --build --preset ci -j $(JOBS)
	ctest --preset ci

asan: setup
	cmake --preset asan
	cmake --build --preset asan -j $(JOBS)
	ctest --preset asan

fuzz: setup
	bash fuzz/run.sh

install: setup
	cmake --preset release >/dev/null
	cmake --build --preset release -j $(JOBS)
	cmake --install build/release --prefix $(PREFIX)

clean:
	rm -rf build out
