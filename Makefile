# Two commands matter (README): `make demo` and `make test`. Both install the
# Debian packages they need first (setup/install-deps.sh).
JOBS   ?= $(shell nproc)
BUILD  ?= build
TBUILD ?= build-test
SIZE   ?= 1024x1024

.PHONY: all deps build demo test test-build fetch clean help

all: build

help:
	@echo "make demo   install deps, build Release, generate, convert, verify and stream the demo scene -> demo/frame.png"
	@echo "make test   install deps, build with ASan+UBSan (clang), fetch meshes, run ctest"
	@echo "make build  Release build into $(BUILD)/ (tools in $(BUILD)/bin)"
	@echo "make fetch  fetch the real test meshes into data_scripts/cache"

deps:
	@./setup/install-deps.sh

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@./data_scripts/demo.sh $(BUILD)/bin demo $(SIZE)

# make test builds and tests oitstream-mpi: IceT from the ParaView debs
# (setup/fetch-icet.sh, 72 MB downloaded once, 200 KB kept), MPI required.
test-build: deps
	./setup/fetch-icet.sh
	cmake -S . -B $(TBUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	  -DOIT_SANITIZE=ON -DOIT_FUZZ=ON -DOIT_REQUIRE_MPI=ON
	cmake --build $(TBUILD) -j $(JOBS)

fetch:
	@./data_scripts/fetch_meshes.sh data_scripts/cache || \
	  echo "make: fetching meshes failed; tests that need them will be skipped" >&2

test: test-build fetch
	cd $(TBUILD) && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD) $(TBUILD) demo
