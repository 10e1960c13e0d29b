#!/usr/bin/env bash
# Installs what the wasm build and the browser tests need, when it is missing:
# the wasm32 target, the wasm-bindgen CLI at the exact version of the crate, npm's
# binaryen (wasm-opt, which shrinks the page's module), esbuild (the one-file page), Debian's Chromium, and
# playwright-core (no browser download); with --wheel, maturin (the Python wheel's builder)
# from pip into a virtual environment of its own, tools/venv, at the version
# python/pyproject.toml names first; with --lab, JupyterLab and anywidget into tools/lab.
# Fast when all is there.
set -euo pipefail
cd "$(dirname "$0")/.."

want=$(sed -n 's/^wasm-bindgen = "=\([0-9.]*\)".*/\1/p' crates/smoothlab-page/Cargo.toml)
[ -n "$want" ] || { echo "ensure-tools: cannot read the wasm-bindgen version pin from crates/smoothlab-page/Cargo.toml" >&2; exit 1; }

if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
  echo "ensure-tools: adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

have=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
if [ "$have" != "$want" ]; then
  echo "ensure-tools: installing wasm-bindgen-cli $want (found '${have:-none}'; takes a few minutes once)"
  # no --locked: one of its pinned dependencies is not in the registry mirror
  cargo install wasm-bindgen-cli --version "$want"
fi

# npm's binaryen, not Debian's: Debian's older wasm-opt writes a module that fails to load;
# esbuild puts the page in one file (make single, make python)
if [ ! -x tools/node_modules/.bin/wasm-opt ] || [ ! -x tools/node_modules/.bin/esbuild ]; then
  echo "ensure-tools: installing binaryen's wasm-opt and esbuild from npm"
  (cd tools && npm ci --no-audit --no-fund --silent 2>/dev/null || npm install --no-audit --no-fund --silent)
fi

if [ "${1:-}" = "--wheel" ]; then
  maturin_want=$(sed -n 's/^requires = \["maturin>=\([0-9.]*\).*/\1/p' python/pyproject.toml)
  [ -n "$maturin_want" ] || { echo "ensure-tools: cannot read maturin's version from python/pyproject.toml" >&2; exit 1; }
  maturin_have=$(tools/venv/bin/maturin --version 2>/dev/null | awk '{print $2}' || true)
  if [ "$maturin_have" != "$maturin_want" ]; then
    echo "ensure-tools: installing maturin $maturin_want into tools/venv (found '${maturin_have:-none}')"
    [ -x tools/venv/bin/python ] || python3 -m venv tools/venv
    tools/venv/bin/pip install -q --disable-pip-version-check "maturin==$maturin_want"
  fi
fi

# --lab: JupyterLab 4.6 and anywidget (the widget's tests in a real notebook) into a
# virtual environment of their own, tools/lab
if [ "${1:-}" = "--lab" ]; then
  if ! tools/lab/bin/python -c 'import jupyterlab, anywidget, numpy; assert jupyterlab.__version__.startswith("4.6.")' 2>/dev/null; then
    echo "ensure-tools: installing JupyterLab 4.6 and anywidget into tools/lab"
    [ -x tools/lab/bin/python ] || python3 -m venv tools/lab
    tools/lab/bin/pip install -q --disable-pip-version-check "jupyterlab>=4.6,<4.7" anywidget numpy
  fi
fi

if [ "${1:-}" = "--browser" ]; then
  if [ ! -x /usr/bin/chromium ]; then
    echo "ensure-tools: installing Debian's chromium"
    if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium >/dev/null
  fi
  if [ ! -d tests/browser/node_modules/playwright-core ] || [ ! -d tests/browser/node_modules/reveal.js ]; then
    echo "ensure-tools: installing playwright-core (no browser download) and reveal.js (the slides suite's deck)"
    (cd tests/browser && npm ci --no-audit --no-fund --silent 2>/dev/null || npm install --no-audit --no-fund --silent)
  fi
fi
