#!/usr/bin/env bash
# Creates .venv with the SIL harness's pinned dependencies (idempotent).
set -euo pipefail
cd "$(dirname "$0")/.."
echo "setup_venv: nothing to install yet"
