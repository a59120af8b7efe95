# batten: `make demo` builds the example hulls headless; `make test` runs every test.
# Both work on a fresh machine with Rust and Python 3.11: they make a local venv (.venv) with
# the pinned tools of requirements-dev.txt, build the Rust module into build/, and reuse both.

PYTHON ?= python3.11
VENV ?= .venv
VPY := $(VENV)/bin/python
PROFILE ?= dev
WHEEL_DIR := build/wheels/$(PROFILE)
NATIVE_DIR := build/native/$(PROFILE)
EXT_DIR := build/extension/$(PROFILE)
OUT ?= out
# CI (CI=true) runs the proptests from this fixed seed, so a failure there replays exactly;
# local runs stay random. Failures found either way persist in tests/*.proptest-regressions.
CI_PROPTEST_SEED := 12

.PHONY: demo test test-compat fuzz extension package native venv sysdeps lint fmt bench clean

demo: venv sysdeps
	$(MAKE) --no-print-directory native PROFILE=release
	PYTHONPATH=build/native/release:addon $(VPY) blender_scripts/demo.py -- --out $(OUT) --zebra

test: venv sysdeps lint
	$(if $(CI),PROPTEST_RNG_SEED=$(CI_PROPTEST_SEED) )cargo test -p batten-core
	$(MAKE) --no-print-directory package PROFILE=dev
	PYTHONPATH=build/native/dev $(VPY) -m pytest -q tests/plain
	BATTEN_EXTENSION_ZIP="$$(ls $(abspath build/extension/dev)/batten-*.zip)" \
	  PYTHONPATH=build/native/dev:addon $(VPY) -m pytest -q --ignore=tests/plain tests

## The older Blenders the extension supports (issue 20; blender_manifest.toml
## blender_version_min): the bpy suite on the latest bpy of each LTS line, each in its own
## venv (.venv-bpy42, .venv-bpy45) made on demand from requirements-dev.txt with its bpy pin
## swapped. `make test` stays on requirements-dev.txt's bpy; COMPAT=42 runs one version;
## `make test-bpy42` runs one on what the last `make test` built (as .ci/run does).
BPY_42 := 4.2.23
BPY_45 := 4.5.15
COMPAT ?= 42 45

test-compat: venv sysdeps
	$(MAKE) --no-print-directory package PROFILE=dev
	$(foreach v,$(COMPAT),$(MAKE) --no-print-directory test-bpy$(v) &&) true

test-bpy%: .venv-bpy%/.installed
	BATTEN_EXTENSION_ZIP="$$(ls $(abspath build/extension/dev)/batten-*.zip)" \
	  PYTHONPATH=build/native/dev:addon .venv-bpy$*/bin/python -m pytest -q --ignore=tests/plain tests

.venv-bpy%/.installed: requirements-dev.txt
	test -n "$(BPY_$*)" || { echo "no bpy version for $* (BPY_$* in the Makefile)" >&2; exit 1; }
	test -x .venv-bpy$*/bin/python || $(PYTHON) -m venv .venv-bpy$*
	grep -v '^bpy==' requirements-dev.txt > .venv-bpy$*/requirements.txt
	.venv-bpy$*/bin/python -m pip install --quiet --upgrade pip
	.venv-bpy$*/bin/python -m pip install --quiet -r .venv-bpy$*/requirements.txt bpy==$(BPY_$*)
	touch $@

# Kept after a run (make would delete a pattern rule's intermediate file).
.PRECIOUS: .venv-bpy%/.installed

## Fuzzing (issue 21): the core's proptest targets (rust/batten-core/tests/fuzz) and the
## hypothesis tests (tests/plain/test_fuzz_native.py, tests/test_fuzz_api.py) with a long
## budget, round after round with fresh seeds for FUZZ_MINUTES; stops at the first failure,
## which stays in the proptest-regressions files / hypothesis database (.hypothesis/) to
## replay; a Python call that hangs ends pytest and is printed from FUZZ_HANG. FUZZ_SKIP names
## core targets to leave out (e.g. FUZZ_SKIP=fit::).
FUZZ_MINUTES ?= 10
FUZZ_CASES ?= 40000
FUZZ_SKIP ?=
FUZZ_HANG := $(abspath build)/fuzz_hang.txt
fuzz: venv sysdeps
	$(MAKE) --no-print-directory native PROFILE=dev
	end=$$(( $$(date +%s) + 60 * $(FUZZ_MINUTES) )); round=0; \
	while [ $$(date +%s) -lt $$end ]; do \
	  round=$$((round + 1)); echo "fuzz round $$round ($$(( (end - $$(date +%s)) / 60 )) min left)"; \
	  BATTEN_FUZZ_CASES=$(FUZZ_CASES) cargo test -p batten-core --test fuzz -- $(addprefix --skip ,$(FUZZ_SKIP)) || exit 1; \
	  BATTEN_FUZZ_PROFILE=long BATTEN_FUZZ_HANG_REPORT=$(FUZZ_HANG) PYTHONPATH=build/native/dev \
	    $(VPY) -m pytest -q tests/plain/test_fuzz_native.py || { cat $(FUZZ_HANG); exit 1; }; \
	  BATTEN_FUZZ_PROFILE=long BATTEN_FUZZ_HANG_REPORT=$(FUZZ_HANG) PYTHONPATH=build/native/dev:addon \
	    $(VPY) -m pytest -q tests/test_fuzz_api.py || { cat $(FUZZ_HANG); exit 1; }; \
	done

## The installable Blender extension zip (release build) in build/extension/release/.
extension: venv
	$(MAKE) --no-print-directory package PROFILE=release
	@ls build/extension/release/*.zip

package: native
	$(VPY) blender_scripts/build_extension.py --wheel-dir $(WHEEL_DIR) --out $(EXT_DIR)

## Test builds (dev) carry the test hooks (`_panic_for_tests`); release builds never do.
## Both are linked by zig (the pinned `ziglang`, found as `python3 -m ziglang` on the venv's
## PATH) against glibc 2.28, Blender's own Linux baseline: a manylinux_2_28 wheel, whatever
## glibc builds it (blender_scripts/build_extension.py checks it with auditwheel).
MANYLINUX := manylinux_2_28
native: venv
	rm -rf $(WHEEL_DIR) $(NATIVE_DIR)
	PATH="$(abspath $(VENV))/bin:$$PATH" $(VPY) -m maturin build --quiet --profile $(PROFILE) \
	  --zig --compatibility $(MANYLINUX) $(if $(filter dev,$(PROFILE)),--features test-hooks) --out $(WHEEL_DIR)
	$(VPY) -m zipfile -e $(WHEEL_DIR)/*.whl $(NATIVE_DIR)

venv: $(VENV)/.installed

$(VENV)/.installed: requirements-dev.txt
	test -x $(VPY) || $(PYTHON) -m venv $(VENV)
	$(VPY) -m pip install --quiet --upgrade pip
	$(VPY) -m pip install --quiet -r requirements-dev.txt
	touch $@

sysdeps:
	bash blender_scripts/system_deps.sh

## Lints: rustfmt, clippy (also with the test hooks), ruff, and stubtest (the .pyi of
## batten_native must match the built module).
lint: venv native
	cargo fmt --all --check
	cargo clippy --workspace --all-targets --quiet -- -D warnings
	cargo clippy -p batten-py --features test-hooks --quiet -- -D warnings
	$(VPY) -m ruff check --quiet addon tests blender_scripts examples rust/batten-py/python
	cd $(NATIVE_DIR) && $(abspath $(VPY)) -m mypy.stubtest batten_native

fmt: venv
	cargo fmt --all
	$(VPY) -m ruff check --fix --quiet addon tests blender_scripts examples rust/batten-py/python
	$(VPY) -m ruff format --quiet addon tests blender_scripts examples rust/batten-py/python

## Speed figures: criterion in the core, and the Python-side benchmarks beside their peers
## (scipy; navaltoolbox when NAVALTOOLBOX names a folder it was pip-installed into with
## --target: AGPL, so never into the venv).
bench: venv sysdeps
	cargo bench -p batten-core
	$(MAKE) --no-print-directory native PROFILE=release
	PYTHONPATH=build/native/release:addon $(VPY) blender_scripts/bench_curves.py
	PYTHONPATH=build/native/release:addon $(VPY) blender_scripts/bench_fairing.py
	PYTHONPATH=build/native/release:addon $(VPY) blender_scripts/bench_import.py
	PYTHONPATH=build/native/release:addon $(VPY) blender_scripts/bench_hydro_surface.py
	PYTHONPATH=build/native/release:addon$(if $(NAVALTOOLBOX),:$(NAVALTOOLBOX)) $(VPY) blender_scripts/bench_hydrostatics.py

clean:
	rm -rf build $(OUT) target
