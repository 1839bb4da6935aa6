#!/usr/bin/env bash
# The whole host unit suite built with AddressSanitizer + UndefinedBehaviorSanitizer
# (-fno-sanitize-recover=all: any finding, signed overflow included, fails),
# then one SIL scenario flown by the sanitized host board.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup_venv.sh
cmake --workflow --preset sanitize

board=build/sanitize/boards/sil/libhelical_sil_board.so
# (nm's whole output is read first: grep -q would close the pipe early and
# pipefail would report nm's SIGPIPE as a failure)
symbols="$(nm -D "$board")"
if ! grep -q __asan_init <<<"$symbols"; then
  echo "sanitize: $board is not instrumented" >&2
  exit 1
fi
echo "== SIL default scenario with the sanitized board"
# Python itself is not instrumented: the runtime is preloaded, leaks of the
# interpreter are not ours to report.
LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
HT_SIL_BOARD_LIB="$board" MPLBACKEND=Agg \
  .venv/bin/python -m helical_sil run sil/scenarios/default.toml --out build/sanitize/sil_default
