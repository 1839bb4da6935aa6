#!/usr/bin/env bash
# The README's test command: every test this machine can run.
#  1. the Python venv of the SIL harness (pinned packages from PyPI),
#  2. the host build and all host tests through ctest (unit, tools, sil),
#  3. the cross builds, when arm-none-eabi-gcc is installed (else: said and skipped).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup_venv.sh
cmake --workflow --preset host
scripts/cross_builds.sh
