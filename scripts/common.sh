#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Sourced by every script (demo.sh, test.sh, sanitize.sh, accuracy/, reliability/ ...): install what is missing (Debian bookworm
# packages only), then configure and build incrementally. Idempotent: a second run installs
# nothing and rebuilds only what changed.
set -euo pipefail

DYNOBJ_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# Why each package is needed: docs/architecture.md, "Dependencies".
DYNOBJ_PACKAGES=(cmake make g++ libmrpt-dev mrpt-apps mrpt-common libopencv-dev libeigen3-dev
                 libnanoflann-dev libgtest-dev libpcap-dev nlohmann-json3-dev libisal-dev zlib1g-dev
                 libcpp-httplib-dev pybind11-dev python3-dev python3-numpy python3-pytest)

log() { printf '[dynobj] %s\n' "$*"; }
# intensity_model_of <sensor preset>: the intensity model of its make (Velodyne presets vlp-*,
# hdl-*: velodyne 0-255; the others: ouster signal), as dynobj-sim's intensity.model takes it.
intensity_model_of() { case "$1" in vlp-*|hdl-*) echo velodyne ;; *) echo ouster ;; esac; }

# ensure_packages [extra packages...]
ensure_packages() {
  local missing=() p
  for p in "${DYNOBJ_PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    log "all packages present"
    return 0
  fi
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo=sudo
  fi
  log "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# build_project <build-dir> [extra cmake args...]
build_project() {
  local dir="$1"
  shift
  log "configuring ${dir}"
  cmake -S "$DYNOBJ_ROOT" -B "$dir" -DCMAKE_BUILD_TYPE="${DYNOBJ_BUILD_TYPE:-Release}" "$@" >/dev/null
  log "building ${dir} ($(nproc) jobs)"
  cmake --build "$dir" -j "$(nproc)"
}

# use_apps: the accuracy scripts' build. Sets BUILD_DIR (DYNOBJ_BUILD_DIR, default build/), builds
# it unless DYNOBJ_SKIP_BUILD=1 (then it is used as built), sets BIN (its apps/) and OUT
# (DYNOBJ_ACCURACY_OUT, default out/accuracy/).
use_apps() {
  BUILD_DIR="${DYNOBJ_BUILD_DIR:-$DYNOBJ_ROOT/build}"
  [ "${DYNOBJ_SKIP_BUILD:-0}" = 1 ] || build_project "$BUILD_DIR"
  BIN="$BUILD_DIR/apps"
  OUT="${DYNOBJ_ACCURACY_OUT:-$DYNOBJ_ROOT/out/accuracy}"
}
