#!/usr/bin/env bash
# The project's test command: installs what the tests need if it is missing, then runs every
# test of the workspace. Works on a fresh Debian 12 machine with the Rust toolchain.
#   LinuxCNC's standalone G-code interpreter `rs274` (Debian package linuxcnc-uspace) checks the
#   exported NC programs end to end.
set -euo pipefail
cd "$(dirname "$0")/.."

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

if ! command -v rs274 >/dev/null 2>&1; then
    echo "test.sh: installing LinuxCNC's interpreter (linuxcnc-uspace) for the NC tests"
    as_root apt-get update -qq
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends linuxcnc-uspace >/dev/null
fi

cargo test --release --workspace "$@"
