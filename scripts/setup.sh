#!/usr/bin/env bash
# Installs every Debian 12 package the rover stack needs to build, test and run.
#
# Idempotent: packages already installed are skipped, and nothing is done when all are present.
# Without root (and without passwordless sudo) it prints the exact command to run and exits 2.
#
# Test-only tool: the reference MCAP implementation (@mcap/core on Node.js) for core/mcap's
# interop test, installed with `npm ci` from tests/tools/mcap-node/package-lock.json into that
# folder's node_modules (Node.js and npm come from Debian when the machine has none).
#
# Usage: scripts/setup.sh [--check]
#   --check   only report what is missing; exit 1 if anything is.
set -euo pipefail
cd "$(dirname "$0")/.."
MCAP_NODE_DIR=tests/tools/mcap-node

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build ccache lld pkg-config git
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
  # DDS Security keys (roverctl security)
  openssl
  # campaigns through Slurm (roverctl run --backend slurm; scripts/slurm-local.sh)
  slurm-client slurmctld slurmd munge
)

# Node.js and npm for the interop test's tool: any node already on the machine will do (it may
# come from elsewhere than Debian, with npm bundled); else Debian's. Where the tool's folder is
# absent (the Docker image copies only this script), neither is installed.
NODE_TOOL=0
[[ -f "$MCAP_NODE_DIR/package-lock.json" ]] && NODE_TOOL=1
if [[ $NODE_TOOL -eq 1 ]] && { ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; }; then
  PACKAGES+=(nodejs npm)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# The npm tool is current when node_modules was installed from today's package-lock.json.
lock_sum=""
[[ $NODE_TOOL -eq 1 ]] && lock_sum=$(sha256sum "$MCAP_NODE_DIR/package-lock.json" | cut -d' ' -f1)
stamp="$MCAP_NODE_DIR/node_modules/.rover-installed-lock"
node_tool_current() {
  [[ $NODE_TOOL -eq 0 ]] || [[ -f "$stamp" && "$(cat "$stamp")" == "$lock_sum" ]]
}

install_node_tool() {
  if [[ $NODE_TOOL -eq 0 ]]; then
    echo "setup: no $MCAP_NODE_DIR here: the test-only npm tool is not installed"
    return 0
  fi
  if node_tool_current; then
    echo "setup: $MCAP_NODE_DIR: @mcap/core present"
    return 0
  fi
  echo "setup: $MCAP_NODE_DIR: npm ci (test-only: @mcap/core and its codecs)"
  (cd "$MCAP_NODE_DIR" && npm ci --no-audit --no-fund --loglevel=error) || {
    echo "setup: npm ci failed in $MCAP_NODE_DIR; the MCAP interop test needs it" >&2
    exit 1
  }
  echo "$lock_sum" > "$stamp"
}

if [[ "${1:-}" == "--check" ]]; then
  status=0
  if [[ ${#missing[@]} -ne 0 ]]; then
    echo "setup: missing packages: ${missing[*]}"
    status=1
  fi
  if ! node_tool_current; then
    echo "setup: $MCAP_NODE_DIR/node_modules is missing or stale (npm ci)"
    status=1
  fi
  [[ $status -eq 0 ]] && echo "setup: all ${#PACKAGES[@]} packages and the npm tool present"
  exit $status
fi

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  install_node_tool
  exit 0
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
install_node_tool
echo "setup: done"
