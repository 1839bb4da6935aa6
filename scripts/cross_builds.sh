#!/usr/bin/env bash
# Cross builds of the library and firmware; skipped (and said so) without the toolchain.
#
# With arm-none-eabi-gcc on PATH: the STM32F405 image (preset stm32f4), the
# Matek F405-WING image (preset matekf405wing) and the library alone for
# Cortex-M0/M3/M4, then sizes, the worst control-tick stack (from
# -fstack-usage/-fcallgraph-info), the Matek image's worst interrupt stack
# and tick time budget (matek_report below), and the M0 no-float check.
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

for preset in stm32f4 matekf405wing cortex-m0 cortex-m3 cortex-m4; do
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
#include "helical/law/helical_turn.h"
#include "helical/output/mixer.h"
#include "helical/output/output_stage.h"
#include "helical/math/q14.h"
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
    python3 tools/image/map_usage.py "$dir/law_image.map"
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
    python3 tools/image/map_usage.py build/stm32f4/boards/stm32f4/ht_stm32f4.map || true
    echo
    echo "== law + output stage linked alone (build/stm32f4/law_image), after --gc-sections"
    usage=$(law_image || true)
    echo "$usage"
    linked=$(echo "$usage" | awk '/^total linked/ {print $3}')
    target "M4 library flash linked by the image (law + output stage) B" "${linked:-999999}" 4096
    echo
    echo "== control tick stack (worst path from fw_step, the board tick's one call; -fstack-usage frames)"
    stack_out=$(python3 tools/image/stack_depth.py build/stm32f4 fw_step || true)
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

# --- the Matek F405-WING image (boards/matekf405wing) -----------------------
# Flash, RAM, the worst stack of each interrupt handler and of the control
# loop (main: board_wait_tick, board_sensors_read, board_rc_read_us, fw_step,
# the pulses; from -fstack-usage/-fcallgraph-info, the bus callbacks named
# for each indirect call), and the control tick's worst-case time with every
# driver active: the firmware step measured (QEMU -icount on
# ht_matekf405wing_budget.elf: instructions), plus the board's bus and parse
# work counted statically from the configured clocks (see the printout).
matek_report() {
    local b=build/matekf405wing
    local elf=$b/boards/matekf405wing/ht_matekf405wing.elf
    echo
    echo "== Matek F405-WING image (preset matekf405wing, receiver $(sed -n 's/^HT_MATEK_RX:STRING=//p' $b/CMakeCache.txt))"
    arm-none-eabi-size "$elf" "$b/boards/matekf405wing/ht_matekf405wing_hil.elf"
    local sz
    sz=$(arm-none-eabi-size "$elf" | tail -1)
    echo "  flash (text + data): $(echo "$sz" | awk '{print $1 + $2}') B of 1 MiB (sectors 1-2 kept for parameters)"
    echo "  RAM (data + bss, static): $(echo "$sz" | awk '{print $2 + $3}') B of 128 KiB (+ the stack below)"
    [ "$have_python" = 1 ] || return 0
    local dirs=$b/boards/matekf405wing/CMakeFiles/ht_matekf405wing.dir:$b/src:$b/firmware
    local ind=(--indirect fs_push=sbus_classify,sbus_check,crsf_classify,crsf_check,ubx_classify,ubx_check
        --indirect gps_ubx_link_poll=gps_write,gps_set_baud --indirect send_step=gps_write,gps_set_baud
        --indirect start_probe=gps_write,gps_set_baud --indirect read_regs=stm32_i2c_write_read
        --indirect write_reg=stm32_i2c_write_read --indirect ms4525_update=stm32_i2c_write_read
        --indirect imu_spi_read_regs=stm32_spi_bus_xfer --indirect imu_spi_write_reg=stm32_spi_bus_xfer
        --indirect imu_spi_set_clock=stm32_spi_bus_set_clock
        --indirect mpu6000_init=matek_delay_us,stm32_spi_bus_xfer
        --indirect icm42688p_init=matek_delay_us,stm32_spi_bus_xfer
        --indirect param_store_load=stm32_param_flash_read
        --indirect scan_slot=stm32_param_flash_read --indirect slot_blank=stm32_param_flash_read)
    local isrs=(SysTick_Handler EXTI4_IRQHandler USART3_IRQHandler) syms h
    syms=$(arm-none-eabi-nm "$elf")
    for h in USART2_IRQHandler USART6_IRQHandler TIM5_IRQHandler UART4_IRQHandler; do # the receiver's, the MAVLink link's
        if echo "$syms" | grep -q " T $h\$"; then
            isrs+=("$h")
        fi
    done
    echo
    echo "== Matek F405-WING stack (worst paths; -fstack-usage frames)"
    local out
    out=$(python3 tools/image/stack_depth.py "$dirs" main fw_step "${isrs[@]}" "${ind[@]}" || true)
    echo "$out"
    local loop_stack isr_stack
    loop_stack=$(echo "$out" | sed -n 's/^worst stack of main: \([0-9]*\) bytes.*/\1/p')
    isr_stack=$(echo "$out" | sed -n 's/^worst stack of [A-Za-z0-9]*_\(IRQ\)\{0,1\}Handler: \([0-9]*\) bytes.*/\2/p' | sort -n | tail -1)
    echo "  worst interrupt handler stack: ${isr_stack:-?} B (all at one priority: they never nest)"
    if [ -n "$loop_stack" ] && [ -n "$isr_stack" ]; then
        echo "  control loop + worst handler + 32 B exception frame (soft-float: no FPU state):" \
            "$((loop_stack + isr_stack + 32)) B"
        target "Matek control loop stack B" "$loop_stack" 1024
    fi
    echo
    echo "== Matek F405-WING control tick time budget (one tick = 5 ms at the 200 Hz IMU rate)"
    if ! command -v qemu-system-arm >/dev/null 2>&1; then
        echo "  qemu-system-arm not found: the firmware step's instruction count is not measured"
        return 0
    fi
    local line
    line=$(timeout 60 qemu-system-arm -M netduinoplus2 -display none -monitor none -serial stdio \
        -icount shift=0 -kernel "$b/boards/matekf405wing/ht_matekf405wing_budget.elf" 2>/dev/null |
        grep -m1 '^budget:' || true)
    echo "  measured: $line"
    local cyc
    cyc=$(echo "$line" | sed -n 's/.*step_max_cyc \([0-9]*\).*/\1/p')
    [ -n "$cyc" ] || { echo "  the budget image printed nothing"; return 0; }
    python3 - "$cyc" <<'EOP'
import sys
# fw_step's worst call: QEMU -icount shift=0 runs 1 instruction per ns of
# virtual time; its SysTick counts the 168 MHz model clock: 0.168 per insn.
insn = int(sys.argv[1]) / 0.168
cpi = 1.3        # assumed Cortex-M4 cycles per instruction from flash (5 WS, ART on)
f = 168e6
us = lambda cycles: cycles / f * 1e6
rows = [("fw_step, worst call (measured instructions x CPI)", us(insn * cpi))]
# the board's bus work in its worst tick (counted from the bus clocks):
sck = 84e6 / 8   # SPI1: PCLK2 84 MHz / 8 = 10.5 MHz (MPU-6000 data limit 20 MHz)
rows.append(("IMU: 5 samples x 15-byte SPI burst (+1 us driver each)", 5 * (15 * 8 / sck * 1e6 + 1.0)))
# BMP280 data read at 400 kHz: S, addr+W, reg, Sr, addr+R, 6 bytes, P:
# 9 bytes of 9 bits + ~3 bit times for S/Sr/P = 84 bit times of 2.5 us
rows.append(("baro: BMP280 burst read on I2C1 at 400 kHz (every 4th tick)", 84 * 2.5))
# the pitot's 4-byte read never shares a tick with the baro (tick 8k+1 vs 4k)
rows.append(("GPS: 58 bytes parsed (115200 baud, 5 ms) x ~100 insn", us(58 * 100 * cpi)))
rows.append(("RC: CRSF 210 bytes parsed (420 kbaud, 5 ms) x ~100 insn", us(210 * 100 * cpi)))
rows.append(("receive interrupts: 268 bytes x ~50 cycles", us(268 * 50)))
rows.append(("console: 16 bytes pumped per wake, 5 wakes x ~20 cycles/byte", us(5 * 16 * 20)))
total = sum(r[1] for r in rows)
for name, t in rows:
    print("  %8.1f us  %s" % (t, name))
print("  %8.1f us  total, of 5000 us (%.1f %% of the tick); fw_step %.0f instructions" % (total, total / 50.0, insn))
EOP
}
matek_report

echo
echo "== M0 no-float check"
tools/image/check_no_float.sh arm-none-eabi-nm build/cortex-m0/src/libhelical.a

if [ "$over" = 1 ]; then
    if [ "$strict" = 1 ]; then
        echo "cross_builds: a target is OVER (HT_STRICT_TARGETS=1)" >&2
        exit 1
    fi
    echo "cross_builds: NOTE a target above is OVER (reported, not failed; HT_STRICT_TARGETS=1 fails)"
fi
echo "cross_builds: done"
