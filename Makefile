# ARS: one entry point for newcomers, developers and CI.
#   make demo   install what the demo needs if missing (Debian packages), show the conical pendulum
#               (a window where there is a display; frames, CSV and plots otherwise)
#   make test   install what the tests need if missing, run the whole test suite (Rust, then the
#               Python package's, in the virtual environment .venv it creates)
#   make python install the Python package `ars` into .venv (pip install ./python)
#   make check  everything CI checks: fmt, clippy, tests, docs, benchmarks compile
#   make bench  the Rust-against-native-ODE benchmarks: times (criterion) and
#               instructions per step (callgrind), each printing Rust/C ratios
#   make figures       the thesis' figures (PNG) and their CSVs, into figures/
#   make readme-table  regenerate the README's table of thesis numbers
#   make corpus-table  regenerate docs/corpus.md: ARS on the corpus of robot files from the wild
#   make bench-mujoco  ARS (exact and quick steppers) against MuJoCo per simulated second, side by
#                      side on Gymnasium's MuJoCo models, then on every corpus MJCF file

# What the demo needs: ODE and its bindings, a C compiler (ODE's guard), the plots'
# font, and off-screen rendering on Mesa's software rasteriser. `make demo` installs
# only these, and a C++ compiler where there is a display (the window's build has the
# video encoder, OpenH264, in C++).
DEMO_PACKAGES := libode-dev pkg-config libclang-dev gcc make fonts-dejavu-core \
	libvulkan1 mesa-vulkan-drivers libegl1 libegl-mesa0 libgl1-mesa-dri
WINDOW_PACKAGES := g++
# The Python package's virtual environment (`make python`).
PYTHON_PACKAGES := python3 python3-venv
# What only the tests need: a display server and a pointer driver for the window tests,
# Chromium for the browser replay, ffmpeg to read videos back, and the original ARS's
# PyODE and numpy for the comparison with it. `make test` and CI install these too.
TEST_PACKAGES := xvfb xdotool chromium ffmpeg python3-pyode python3-numpy $(WINDOW_PACKAGES)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

# Installs the Debian packages in $(1) that are missing.
define install_missing
	@missing=""; \
	for p in $(1); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
		echo "Installing Debian packages:$$missing"; \
		$(SUDO) apt-get update -qq && \
		$(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	fi
	@command -v cargo >/dev/null || { echo "cargo not found: install Rust (https://rustup.rs) first"; exit 1; }
endef

.PHONY: deps demo-deps python-deps demo test check bench figures readme-table python python-test \
	corpus-table bench-mujoco

# The Python package is built by pip (maturin, release profile) into this environment.
VENV := .venv
PYTHON := $(VENV)/bin/python

# Everything: what the demo, the Python package and the tests need.
deps:
	$(call install_missing,$(DEMO_PACKAGES) $(PYTHON_PACKAGES) $(TEST_PACKAGES))

# The window's packages only where there is a display (make imports DISPLAY).
demo-deps:
	$(call install_missing,$(DEMO_PACKAGES) $(if $(DISPLAY)$(WAYLAND_DISPLAY),$(WINDOW_PACKAGES)))

python-deps:
	$(call install_missing,$(DEMO_PACKAGES) $(WINDOW_PACKAGES) $(PYTHON_PACKAGES))

# Where there is a display: the conical pendulum in a window. Otherwise: off-screen
# frames, the CSV and the plots of the conical pendulum into demo-output/, from a build
# without the window and the video encoder (egui's crates and OpenH264's C++: a
# seventh of a cold build), which a machine with no display cannot use.
# The demo is built in the dev profile: a cold build takes a third of a release build's
# time (the physics is native ODE either way, and the pictures Mesa's), and `make test`
# then reuses the dependencies it built.
demo: demo-deps
	@if [ -n "$${DISPLAY}$${WAYLAND_DISPLAY}" ]; then \
		cargo run --locked --example conical_pendulum -- --window; \
	else \
		cargo run --locked --no-default-features --features viewer --example conical_pendulum -- \
			--duration 10 --screenshots demo-output/frames --frame-every 10 --size 800x600 \
			--csv demo-output/conical_pendulum.csv --every 40 --plot demo-output && \
		echo "no display: frames, CSV and plots of the conical pendulum are in $(CURDIR)/demo-output"; \
	fi

test: deps
	cargo test --workspace --locked
	$(MAKE) python-test

$(PYTHON):
	python3 -m venv $(VENV)
	$(PYTHON) -m pip install --quiet --upgrade pip

python: python-deps $(PYTHON)
	$(PYTHON) -m pip install --quiet numpy pytest ruff mypy ray mujoco "gymnasium>=1.0" nbclient ipykernel mcap mcap-ros2-support rosbags cyclonedds
	$(PYTHON) -m pip install --quiet --force-reinstall --no-deps ./python

python-test: python
	$(VENV)/bin/ruff check python tools
	$(VENV)/bin/ruff format --check python tools
	$(VENV)/bin/pytest -q python/tests

check: deps
	cargo fmt --all -- --check
	cargo clippy --workspace --all-targets --locked -- -D warnings
	cargo test --workspace --locked
	RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked
	RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --locked --document-private-items
	cargo build --workspace --benches --locked

bench: deps
	cargo bench -p ars-benches --no-default-features --bench native_comparison
	cargo bench -p ars-benches --no-default-features --bench step_cost

figures: demo-deps
	cargo build --release --examples
	cargo run --release --example falling_ball_sensors -- --csv figures/falling_ball.csv --plot figures
	cargo run --release --example laser -- --csv figures/laser.csv --plot figures
	cargo run --release --example conical_pendulum -- --csv figures/conical_pendulum.csv --every 40 --plot figures
	cargo run --release --example speed_profile -- --csv figures/speed_profile.csv --plot figures
	cargo run --release --example sinusoidal_terrain -- --csv figures/sinusoidal_terrain.csv --plot figures
	cargo run --release --example user_driven -- --paper --csv figures/user_driven.csv --plot figures
	@echo "figures written to $(CURDIR)/figures"

readme-table: demo-deps
	cargo run --release --example thesis_table -- --write-readme

# docs/corpus.md, from the corpus test itself (python/tests/test_corpus.py, which `make test`
# runs): the same report, so the page shows what CI holds to its floors. The corpus is fetched
# into ~/.cache/ars-corpus if missing (about 650 MB, once). The page is copied even when a
# floor fails (it then shows why), and the target fails with the test.
CORPUS_REPORT := $(or $(ARS_CORPUS_CACHE),$(HOME)/.cache/ars-corpus)/report-test
corpus-table: python
	@status=0; ARS_CORPUS_REPORT="$(CORPUS_REPORT)" $(VENV)/bin/pytest -q python/tests/test_corpus.py \
		|| status=$$?; \
	cp "$(CORPUS_REPORT)/corpus.md" docs/corpus.md && echo "written: docs/corpus.md"; \
	exit $$status

# ARS against MuJoCo per simulated second, in one run, one file after the other (issue 37).
bench-mujoco: python
	$(PYTHON) tools/corpus/fetch.py
	$(PYTHON) tools/corpus/speed.py --gymnasium
	$(PYTHON) tools/corpus/speed.py --repeat 1 --json corpus-speed.json
