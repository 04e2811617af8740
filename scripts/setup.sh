#!/usr/bin/env bash
# Installs every Debian 12 package the rover stack needs to build, test and run.
#
# Idempotent: packages already installed are skipped, and nothing is done when all are present.
# Without root (and without passwordless sudo) it prints the exact command to run and exits 2.
#
# Usage: scripts/setup.sh [--check]
#   --check   only report what is missing; exit 1 if anything is.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build ccache pkg-config git
  # DDS
  cyclonedds-dev cyclonedds-tools
  # maths, vision, physics, optimisation
  libeigen3-dev libopencv-dev libsimbody-dev libnlopt-cxx-dev
  # configuration, CLI, logging
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libspdlog-dev libfmt-dev
  # MCAP recordings: chunk compression
  libzstd-dev liblz4-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # headless rendering (EGL surfaceless on Mesa llvmpipe)
  libegl-dev libgl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
  # compose-file validation (no engine is needed for `docker-compose config`)
  docker-compose
  # tools used by tests: XML validation of JUnit output, process inspection
  libxml2-utils procps python3
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

if [[ "${1:-}" == "--check" ]]; then
  echo "setup: missing packages: ${missing[*]}"
  exit 1
fi

cmd=(apt-get install -y --no-install-recommends "${missing[@]}")
if [[ $(id -u) -eq 0 ]]; then
  SUDO=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  SUDO=(sudo)
else
  echo "setup: ${#missing[@]} packages are missing and this user cannot install them." >&2
  echo "setup: run as root:" >&2
  echo "  apt-get update && ${cmd[*]}" >&2
  exit 2
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -q
"${SUDO[@]}" "${cmd[@]}"
echo "setup: done"
