#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and runs each for a
# bounded time from its seed corpus, on one core each (no -jobs).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
#   FUZZ_RUNS=N   stop each target after N executions instead (no time limit)
# e.g. FUZZ_RUNS=10000000 scripts/fuzz.sh 0 fuzz_hil_decoder
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
only=("$@")
cc="$(command -v clang-14 || command -v clang || true)"
if [ -z "$cc" ]; then
  echo "fuzz: clang not found (apt-get install clang-14 libclang-rt-14-dev)" >&2
  exit 1
fi
# Everything (the library too) is instrumented for coverage and sanitized;
# only the fuzz targets link libFuzzer's main.
cmake -S . -B build/fuzz -G Ninja -DCMAKE_C_COMPILER="$cc" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all" \
  -DHT_BUILD_FUZZERS=ON -DHT_BUILD_TOOLS=ON >/dev/null
if [ "${#only[@]}" -gt 0 ]; then
  cmake --build build/fuzz --target "${only[@]}"
else
  cmake --build build/fuzz --target fuzzers
fi
if [ -n "${FUZZ_RUNS:-}" ]; then
  limit=(-runs="$FUZZ_RUNS")
else
  limit=(-max_total_time="$seconds")
fi
status=0
for target in build/fuzz/tests/fuzz/fuzz_*; do
  [ -x "$target" ] || continue
  name="$(basename "$target")"
  if [ "${#only[@]}" -gt 0 ] && [[ ! " ${only[*]} " =~ " $name " ]]; then
    continue
  fi
  corpus="tests/fuzz/corpus/${name#fuzz_}"
  work="build/fuzz/corpus-${name#fuzz_}"
  mkdir -p "$work"
  echo "== $name: ${limit[*]} from $corpus"
  if ! "$target" "${limit[@]}" -print_final_stats=1 -max_len=512 \
      -artifact_prefix="build/fuzz/${name}-" "$work" "$corpus" 2> "build/fuzz/$name.log"; then
    echo "fuzz: $name FAILED: see build/fuzz/$name.log and build/fuzz/${name}-crash-*" >&2
    tail -n 30 "build/fuzz/$name.log" >&2
    status=1
  fi
  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec|cov:" "build/fuzz/$name.log" | tail -n 3
done
exit "$status"
