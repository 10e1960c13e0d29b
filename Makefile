# smoothlab — the two commands of the quick start are `make serve` and `make test`.
#   make serve   build the page (wasm + www/) and serve it on http://127.0.0.1:8000
#   make test    every test: the docs' sizes, clippy (host and wasm32) and the docs, native unit/integration tests, wasm build, browser tests
#   make site    build the complete static site into www/ (www/pkg is generated)
#   make single  the page as one file that opens from file:// (target/smoothlab.html)
#   make python  the notebook widget's module into python/smoothlab/static/
#   make wheel   the Python package as one wheel, target/wheels/smoothlab-*.whl (then: pip install it)
#   make figures        the docs' pictures and the papers' figures (docs/figures.md)
#   make figure-sizes   screenshots of every figure at 800×450, 520×520, 1280×720 and on a phone (docs/figures/sizes/)
#   make reproduction   rerun the papers' experiments into docs/reproduction.md, and its tables into
#                       docs/reproduction.json for the page's tour (a few minutes)
#   make performance    rerun the benchmarks (native, in Chromium, in the page) into docs/performance.md (~15 minutes)

WASM := target/wasm32-unknown-unknown/release/smoothlab_page.wasm
PORT ?= 8000
CARGO ?= cargo

.PHONY: serve test check-docs site single python wheel python-test lab-test lint unit wasm browser tools browser-tools figures figure-sizes reproduction performance

serve: site
	@echo "smoothlab playground: http://127.0.0.1:$(PORT)/"
	python3 -m http.server $(PORT) --bind 127.0.0.1 --directory www

test: check-docs lint unit site browser
	@$(MAKE) --no-print-directory python-test NEED_PAGE_STATE=1
	@$(MAKE) --no-print-directory lab-test

# the docs a reader can use: README.md and ARCHITECTURE.md at most 150 lines, docs/performance.md
# at most 25,000 bytes, no line of the docs over 400 characters
check-docs:
	python3 scripts/check-docs.py

# clippy for the host (every crate and target: libs, CLI, tests, programs, benches) and for
# the page's wasm32 build (the wasm layer compiles only there), then the docs with broken
# links denied
lint: tools
	$(CARGO) clippy --workspace --all-targets -- -D warnings
	$(CARGO) clippy -p smoothlab-page --lib --target wasm32-unknown-unknown -- -D warnings
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --workspace --no-deps

unit:
	$(CARGO) test --workspace

tools:
	@scripts/ensure-tools.sh

browser-tools:
	@scripts/ensure-tools.sh --browser

# wasm-bindgen's module, then binaryen's wasm-opt -O3 (601 → 560 KB gzipped when it was added,
# as fast), told that the lowest 1 KB of memory is never addressed (Rust's
# pointers never wrap round to it: the stack lies first and ends at 1 MB, the data after it),
# so a constant added to an address becomes the load's offset (5 KB smaller gzipped, as
# fast). wasm-opt runs only when wasm-bindgen's output or these flags changed (it takes a
# while), its input, flags and output kept in target/wasm-opt/.
WASM_OPT := tools/node_modules/.bin/wasm-opt
WASM_OPT_FLAGS := -O3 --low-memory-unused

site: tools
	$(CARGO) build -p smoothlab-page --lib --release --target wasm32-unknown-unknown
	wasm-bindgen --target web --no-typescript --out-name smoothlab --out-dir target/wasm-bindgen $(WASM)
	@mkdir -p target/wasm-opt www/pkg
	@if ! cmp -s target/wasm-bindgen/smoothlab_bg.wasm target/wasm-opt/input.wasm || \
	    [ "$$(cat target/wasm-opt/flags 2>/dev/null)" != "$(WASM_OPT_FLAGS)" ]; then \
	  echo "$(WASM_OPT) $(WASM_OPT_FLAGS)"; \
	  $(WASM_OPT) $(WASM_OPT_FLAGS) target/wasm-bindgen/smoothlab_bg.wasm -o target/wasm-opt/output.wasm && \
	  cp target/wasm-bindgen/smoothlab_bg.wasm target/wasm-opt/input.wasm && \
	  echo "$(WASM_OPT_FLAGS)" > target/wasm-opt/flags; \
	fi
	cp target/wasm-bindgen/smoothlab.js www/pkg/smoothlab.js
	cp target/wasm-opt/output.wasm www/pkg/smoothlab_bg.wasm
	@ls -l www/pkg/smoothlab_bg.wasm | awk '{print "wasm size: " $$5 " bytes"}'
	@gzip -9c www/pkg/smoothlab_bg.wasm | wc -c | awk '{print "wasm size gzipped: " $$1 " bytes"}'
	node scripts/site-manifest.mjs

# The page as one self-contained file (scripts/single.mjs): opens from file://, offline.
single: site
	node scripts/single.mjs --html target/smoothlab.html

# The notebook widget (python/): its ES module (python/widget/widget.js), the one-file page
# it shows (page.html.gz, shared by every widget of a kernel) and the sheet its arguments are
# checked against, read from the site just built.
python: site
	node scripts/single.mjs --html target/widget-page.html --widget python/smoothlab/static/widget.js --sheet python/smoothlab/static/sheet.json
	gzip -9 -n -c target/widget-page.html > python/smoothlab/static/page.html.gz

# The Python package as one wheel for CPython 3.9 and later (abi3): the native module
# (crates/smoothlab-python, the core compiled for this machine), python/smoothlab and the
# widget's module and sheet (make python). maturin builds it, installed by pip into
# tools/venv (scripts/ensure-tools.sh --wheel) at the version python/pyproject.toml names.
wheel: python
	@scripts/ensure-tools.sh --wheel
	@rm -f target/wheels/smoothlab-*.whl
	cd python && ../tools/venv/bin/maturin build --release --out ../target/wheels
	@ls -l target/wheels/smoothlab-*.whl | awk '{print "wheel size: " $$5 " bytes"}'

# pytest in a virtual environment of its own (target/venv, made once) against the wheel
# as a user installs it (pip install target/wheels/smoothlab-*.whl), run from outside
# python/ so that the source tree is not what is imported; the widget's module is the one
# the browser tests loaded, and the model's state they left (test-output/widget/: make
# test runs the browser first and needs it). The byte-for-byte tests run the command-line
# tool built from the same tree: its debug build, which make test's unit tests have built
# (Rust computes the same bits at every optimisation level: no fast-math, no contraction).
# pytest's own exit code is the target's (5: no test ran).
VENV := target/venv
python-test: wheel
	$(CARGO) build -p smoothlab-cli
	@test -x $(VENV)/bin/python || python3 -m venv $(VENV)
	@$(VENV)/bin/python -c 'import anywidget, numpy, meshio, pytest' 2>/dev/null || \
	  $(VENV)/bin/pip install -q --disable-pip-version-check anywidget numpy meshio pytest
	$(VENV)/bin/pip install -q --disable-pip-version-check --no-deps --force-reinstall target/wheels/smoothlab-*.whl
	cd target && SMOOTHLAB_NEED_PAGE_STATE=$(NEED_PAGE_STATE) SMOOTHLAB_CLI=$(CURDIR)/target/debug/smoothlab \
	  venv/bin/pytest -q -p no:cacheprovider --rootdir=$(CURDIR)/python --doctest-modules \
	  $(CURDIR)/python/tests venv/lib/python3*/site-packages/smoothlab

# The notebook widget in a real JupyterLab (tests/browser/jupyterlab.mjs, about 40 s): four
# widgets run, stepped, read back, given another sample, saved with their state (the
# notebook's size measured) and opened again. JupyterLab 4.6 and anywidget live in a
# virtual environment of their own, tools/lab (scripts/ensure-tools.sh --lab, made once),
# the wheel installed into it as a user installs it.
lab-test: wheel browser-tools
	@scripts/ensure-tools.sh --lab
	tools/lab/bin/pip install -q --disable-pip-version-check --no-deps --force-reinstall target/wheels/smoothlab-*.whl
	node tests/browser/jupyterlab.mjs tools/lab

browser: python single browser-tools
	node tests/browser/run.mjs

# the document, and its tables as data for the page's tour: both written from the same numbers
# once every section has run, so a run that fails leaves them as they were
reproduction:
	$(CARGO) run --release -p smoothlab-programs --bin reproduce -- --out docs/reproduction.md --data docs/reproduction.json

# The browser benches first (the wasm bench's JSON feeds the wasm/native table, the page
# bench's the "In the page" section, the page's memory the memory section), then issue 33's
# speed-ups before and after in one run (the CLI of the issue's day built beside this tree's),
# then the native figures.
performance: site browser-tools
	@mkdir -p target/perf
	$(CARGO) build --release -p smoothlab-programs --features parallel --bin perf
	node tests/browser/bench.mjs --nodes 100000 --reps 3 > target/perf/wasm.json
	$(CARGO) run --release -p smoothlab-programs --features parallel --bin perf -- --native-peers target/perf/wasm.json
	node tests/browser/page_bench.mjs --reps 3 > target/perf/page.json
	node tests/browser/page_memory.mjs > target/perf/page-memory.json
	$(CARGO) build --release -p smoothlab-cli --features parallel --bin smoothlab
	python3 scripts/before_after.py > target/perf/before_after.json
	$(CARGO) run --release -p smoothlab-programs --features parallel --bin perf -- --wasm target/perf/wasm.json --page target/perf/page.json --page-memory target/perf/page-memory.json --before-after target/perf/before_after.json --out docs/performance.md

# the docs' pictures (docs/images/), drawn by the CLI from generated meshes, then the
# papers' figures of the page's tour (docs/figures/*.png and docs/figures.md)
figures:
	scripts/figures.sh
	$(CARGO) run --release -p smoothlab-programs --bin figures

# the page's figures as embeds and on a phone, in Chromium (docs/figures/sizes/*.png)
figure-sizes: site browser-tools
	node scripts/figure-sizes.mjs
