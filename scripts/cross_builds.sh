#!/usr/bin/env bash
# Cross builds of the library and firmware; skipped (and said so) without the toolchain.
#
# With arm-none-eabi-gcc on PATH: the STM32F405 image (preset stm32f4) and
# the library alone for Cortex-M0/M3/M4, then sizes, the worst control-tick
# stack (from -fstack-usage/-fcallgraph-info) and the M0 no-float check.
# Fails on a build error or on float symbols in the M0 library. The size and
# stack targets of issue 4 are reported as PASS/OVER; set HT_STRICT_TARGETS=1
# to make an OVER fail the script too.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v arm-none-eabi-gcc >/dev/null 2>&1; then
    echo "SKIPPED cross builds: arm-none-eabi-gcc not found (not built: stm32f4 firmware image," \
        "cortex-m0/m3/m4 library builds, M0 no-float check, size and stack reports;" \
        "install with scripts/install_ci_deps_boards.sh)"
    exit 0
fi

strict=${HT_STRICT_TARGETS:-0}
over=0
target() { # name value limit
    if [ "$2" -le "$3" ]; then
        echo "  PASS $1: $2 <= $3"
    else
        echo "  OVER $1: $2 > $3"
        over=1
    fi
}

for preset in stm32f4 cortex-m0 cortex-m3 cortex-m4; do
    echo "== cmake --workflow --preset $preset"
    cmake --workflow --preset "$preset"
done

image=build/stm32f4/boards/stm32f4/ht_stm32f4.elf
echo
echo "== arm-none-eabi-size: firmware image"
arm-none-eabi-size "$image"
for cpu in cortex-m0 cortex-m3 cortex-m4; do
    echo
    echo "== arm-none-eabi-size: library alone, $cpu (build/$cpu/src/libhelical.a)"
    arm-none-eabi-size -t "build/$cpu/src/libhelical.a"
done

# The issue's library target is "law + output stage": what an image that
# flies the law and drives servos links from libhelical.a. The flight image
# now links the estimator, modes and guidance too (firmware/fw_step.c), so
# that figure comes from a link of its own: the image's libhelical.a with
# exactly the calls the law-and-servo image made (ht_init, ht_step, the
# output stage and RC mixer, q_mul32, q_sat16), --gc-sections, no startup
# code. At c0f007e (before fw_step) this link and the flight image's map
# give the same 4186 B, member by member.
law_image() { # prints map_usage.py's table of the law + output stage link
    local dir=build/stm32f4/law_image
    mkdir -p "$dir"
    cat >"$dir/law_image.c" <<'EOC'
#include "helical/helical_turn.h"
#include "helical/mixer.h"
#include "helical/output_stage.h"
#include "helical/q14.h"
/* the roots the link keeps; everything else is collected by --gc-sections */
void *const law_image_roots[] = {
    (void *)ht_init,            (void *)ht_step,         (void *)q_mul32,    (void *)q_sat16,
    (void *)os_channel_default, (void *)os_config_check, (void *)os_compute, (void *)os_failsafe,
    (void *)os_rc_cal_check,    (void *)os_rc_command};
void law_image_entry(void);
void law_image_entry(void) {}
EOC
    arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfloat-abi=soft -Os -ffunction-sections \
        -fdata-sections -Iinclude -nostartfiles --specs=nano.specs -Wl,--gc-sections \
        -Wl,-e,law_image_entry -Wl,--undefined=law_image_roots -Wl,-Map,"$dir/law_image.map" \
        "$dir/law_image.c" build/stm32f4/src/libhelical.a -o "$dir/law_image.elf"
    python3 boards/common/map_usage.py "$dir/law_image.map"
}

echo
echo "== targets (issue 4)"
m4_totals=$(arm-none-eabi-size -t build/cortex-m4/src/libhelical.a | tail -1)
m4_ram=$(echo "$m4_totals" | awk '{print $2 + $3}')
target "M4 library static RAM, whole archive (data+bss) B" "$m4_ram" 256

have_python=0
if command -v python3 >/dev/null 2>&1; then
    have_python=1
fi

if [ "$have_python" = 1 ]; then
    echo
    echo "== library objects linked into the STM32F4 (Cortex-M4) flight image, after --gc-sections"
    python3 boards/common/map_usage.py build/stm32f4/boards/stm32f4/ht_stm32f4.map || true
    echo
    echo "== law + output stage linked alone (build/stm32f4/law_image), after --gc-sections"
    usage=$(law_image || true)
    echo "$usage"
    linked=$(echo "$usage" | awk '/^total linked/ {print $3}')
    target "M4 library flash linked by the image (law + output stage) B" "${linked:-999999}" 4096
    echo
    echo "== control tick stack (worst path from fw_step, the board tick's one call; -fstack-usage frames)"
    stack_out=$(python3 boards/common/stack_depth.py build/stm32f4 fw_step || true)
    echo "$stack_out"
    tick_stack=$(echo "$stack_out" | sed -n 's/^worst stack of fw_step: \([0-9]*\) bytes.*/\1/p')
    if [ -n "$tick_stack" ]; then
        target "control tick stack B" "$tick_stack" 256
    else
        echo "  OVER control tick stack: could not be computed"
        over=1
    fi
else
    echo
    echo "== control tick stack: python3 not found; the per-function frames (.su):"
    find build/stm32f4 -name '*.su' -exec cat {} + | sort -t"$(printf '\t')" -k2 -n | tail -15
fi

echo
echo "== M0 no-float check"
boards/common/check_no_float.sh arm-none-eabi-nm build/cortex-m0/src/libhelical.a

if [ "$over" = 1 ]; then
    if [ "$strict" = 1 ]; then
        echo "cross_builds: a target is OVER (HT_STRICT_TARGETS=1)" >&2
        exit 1
    fi
    echo "cross_builds: NOTE a target above is OVER (reported, not failed; HT_STRICT_TARGETS=1 fails)"
fi
echo "cross_builds: done"
