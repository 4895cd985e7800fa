# The two commands (README): `make demo` and `make test`. Both install missing Debian packages,
# configure and build into build/; demo then runs the quickstart job on PoCL, test runs ctest.
BUILD ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo
# file: CPack reads the binaries with it to declare the .deb's shared-library dependencies (make package).
# Images: libopenexr-dev and libpng-dev write EXR and PNG, libopenimageio-dev reads them (and compares).
DEPS = build-essential cmake pkgconf pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers \
       opencl-clhpp-headers clinfo libfftw3-dev libvkfft-dev libopenexr-dev libpng-dev libopenimageio-dev \
       openimageio-tools libtbb-dev \
       libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libgtest-dev file libglfw3-dev libgl-dev libopengl-dev
# `make test` also needs a display for the preview's tests (Xvfb, xauth and Mesa's llvmpipe,
# libgl1-mesa-dri), for the farm test (tests/farm/) a real Slurm controller and node on localhost,
# for the portability tests (tests/runtimes/) Oclgrind, and python3 with pip to fetch Intel's OpenCL
# CPU runtime from PyPI into $(BUILD)/intel-opencl (the wheels cached outside $(BUILD): docs/install.md),
# and for the Python package's tests python3-venv and python3-dev.
TEST_DEPS = xvfb xauth libgl1-mesa-dri slurm-wlm munge oclgrind python3 python3-pip python3-venv python3-dev
# `make validate` (opt-in) also needs Python's venv module.
VALIDATE_DEPS = python3-venv
# Kernel build caches live in the build folder so tests and demo reuse them.
export POCL_CACHE_DIR ?= $(CURDIR)/$(BUILD)/pocl-cache
export SEASIM_CACHE_DIR ?= $(CURDIR)/$(BUILD)/seasim-cache

# The Python package (docs/python/README.md): a virtual environment with what builds and tests it.
PYVENV = $(BUILD)/python-venv
PYTHON_PACKAGES = nanobind scikit-build-core numpy pytest tqdm
PYTHON_CMAKE_FLAGS = -DSEASIM_PYTHON=ON -DPython_EXECUTABLE=$(abspath $(PYVENV))/bin/python

.PHONY: demo gallery test test-deps intel-opencl validate deps configure build kernel-store clean fresh-check package install python-venv wheel

demo: kernel-store
	$(BUILD)/seasim run jobs/quickstart.toml --device pocl
	@echo "images and reports: results/quickstart/ (contact sheet: results/quickstart/index.html)"

# The README's gallery (docs/images/gallery.png): the quickstart job's images, in job order, on one
# sheet (OpenImageIO's oiiotool, from openimageio-tools).
GALLERY = flat_sea_noon flat_sea_evening ocean_noon ocean_sunset stage_shafts seabed_IB seabed_wave_caustics rov_lights \
          tropical_shallows muddy_coast jerlov_I jerlov_III seabed_3C jerlov_5C jerlov_9C flat_sea_spectral_canon
gallery: demo
	oiiotool $(foreach n,$(GALLERY),results/quickstart/$(n)/image.png) --mosaic:fit=320x180:pad=4 4x4 -o docs/images/gallery.png
	@echo "gallery: docs/images/gallery.png"

# The test build adds the Python module (SEASIM_PYTHON), which ctest's python.pytest imports.
test: test-deps python-venv intel-opencl
	@$(MAKE) --no-print-directory build CMAKE_FLAGS="$(CMAKE_FLAGS) -DSEASIM_TESTS=ON $(PYTHON_CMAKE_FLAGS)"
	cd $(BUILD) && ctest --output-on-failure -j 2

python-venv:
	@$(MAKE) --no-print-directory deps DEPS="python3-venv python3-dev"
	test -x $(PYVENV)/bin/python || python3 -m venv $(PYVENV)
	$(PYVENV)/bin/python -c "import nanobind, scikit_build_core, numpy, pytest, tqdm" 2>/dev/null || \
	  $(PYVENV)/bin/pip install -q $(PYTHON_PACKAGES)

# A wheel of the Python package into $(BUILD)/, built by scikit-build-core in the build folder itself
# (so only the module is compiled anew), with that folder's CMake generator; then the install prefix
# and the SKBUILD settings it cached are dropped again, so the folder configures as before.
# scikit-build-core deletes CMakeCache.txt and CMakeFiles/ (every object file, and with the cache the
# folder's SEASIM_TESTS) when its record .skbuild-info.json names another interpreter's
# scikit-build-core; the folder is ours, so that record goes first.
wheel: configure python-venv
	rm -f $(BUILD)/.skbuild-info.json
	CMAKE_GENERATOR="$$(sed -n 's/^CMAKE_GENERATOR:INTERNAL=//p' $(BUILD)/CMakeCache.txt)" \
	  $(PYVENV)/bin/pip wheel -q --no-build-isolation --no-deps -w $(BUILD) --config-settings=build-dir=$(BUILD) .
	cmake -S . -B $(BUILD) -UCMAKE_INSTALL_PREFIX -U'SKBUILD*' > /dev/null
	@ls $(BUILD)/seasim-*.whl

test-deps:
	@$(MAKE) --no-print-directory deps DEPS="$(TEST_DEPS)"

# Intel's OpenCL CPU runtime in $(BUILD)/intel-opencl, registered by its own ICD folder (nothing
# system-wide). When it cannot be installed, make test goes on and its tests fail saying why.
intel-opencl: test-deps
	@test -f $(BUILD)/intel-opencl/vendors/intel-cpu.icd || tests/runtimes/install_intel_opencl.sh $(BUILD)/intel-opencl \
	  || echo "warning: Intel's OpenCL CPU runtime could not be installed; the runtimes.intel tests will fail"

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# The kernel store beside the binary ($(BUILD)/kernel-store, installed under share/seasim): every
# shipped scene's and the quickstart job's kernels compiled once for this machine's PoCL, so that a
# render with empty caches (a new user, a farm node of the same CPU and driver) builds none
# (host/device/kernel_store.h). Made again (from empty caches: about a minute on 2 cores) when the
# binary is newer than it.
STORE = $(BUILD)/kernel-store
kernel-store: build
	@if [ ! -f $(STORE)/.made ] || [ $(BUILD)/seasim -nt $(STORE)/.made ]; then \
	  rm -rf $(STORE).new && \
	  $(BUILD)/seasim cache warm --device pocl --store $(STORE).new scenes/*.toml jobs/quickstart.toml && \
	  touch $(STORE).new/.made && rm -rf $(STORE) && mv $(STORE).new $(STORE); \
	fi

configure: deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

# Opt-in, not part of `make test`: seasim's references against Mitsuba 3 on matching scenes.
# A Python virtual environment in $(BUILD)/validate-venv with mitsuba and numpy from PyPI (the scalar
# variants need nothing else); ratio tables into results/validation/: spotlight shafts, the underwater
# flat-bottom scene (level and through Snell's window), the sea seen from above and a spotlight under
# water (about 40 min on the shared 2-core VM).
validate: build
	@$(MAKE) --no-print-directory deps DEPS="$(VALIDATE_DEPS)"
	test -x $(BUILD)/validate-venv/bin/python || python3 -m venv $(BUILD)/validate-venv
	$(BUILD)/validate-venv/bin/pip install -q mitsuba numpy
	$(BUILD)/validate-venv/bin/python tests/validate/mitsuba_shafts.py $(BUILD)/seasim results/validation
	$(BUILD)/validate-venv/bin/python tests/validate/mitsuba_underwater.py $(BUILD)/seasim results/validation
	$(BUILD)/validate-venv/bin/python tests/validate/mitsuba_sea.py $(BUILD)/seasim results/validation
	$(BUILD)/validate-venv/bin/python tests/validate/mitsuba_lamps.py $(BUILD)/seasim results/validation 16 512 2048

# Installs only what is missing (apt-get needs root: sudo is used when not root).
deps:
	@missing=""; for p in $(DEPS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing missing packages:$$missing"; \
	  if [ "$$(id -u)" = 0 ]; then SUDO=; else SUDO=sudo; fi; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
	fi

# A .deb of the binary, its data and examples (CPack; runtime dependencies from dpkg-shlibdeps).
package: kernel-store
	cd $(BUILD) && cpack -G DEB
	@ls $(BUILD)/seasim_*.deb

# cmake --install into PREFIX (default /usr/local): bin/seasim and share/seasim/{data,scenes,jobs,kernel-store}.
PREFIX ?= /usr/local
install: kernel-store
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD)

# The two commands above in a bare Debian 12 root (needs root; slow, not part of CI): tests/fresh_check.sh
fresh-check:
	bash tests/fresh_check.sh
