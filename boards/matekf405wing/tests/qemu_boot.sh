#!/bin/sh
# qemu_boot.sh QEMU ELF [SECONDS] - boot the Matek F405-WING flight image in
# QEMU's netduinoplus2 (an STM32F405 with no devices attached: no IMU, baro,
# pitot, GPS or receiver; RCC, GPIO, I2C, TIM8 and TIM12 unmodelled) and
# check its console (USART1 = -serial #0):
#   - the clock fell back to the HSI (RCC reads 0 there) and said so;
#   - the parameter store was reported (the emulated flash reads 0x00: corrupt);
#   - each missing device was reported: IMU, baro, pitot, GPS, receiver;
#   - the firmware entered its sensor failsafe and the board heard it;
#   - the loop keeps running (at least 3 heartbeats, tick count rising);
#   - the servos sit at their failsafe pulses: S1 aileron 1500, S2 elevator
#     1500, S3 throttle 1000, S4 rudder 1500 us (fw_config_default's
#     5-channel aeroplane, os_channel_default: surfaces at centre, throttle at
#     idle), read back from the TIM4/TIM3 compare registers, which QEMU
#     models (S5..S8 are on TIM8/TIM12, which it does not: they read 0).
# Exits 1 naming the first missing line.
qemu="$1"
elf="$2"
secs="${3:-6}"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
timeout "$secs" "$qemu" -M netduinoplus2 -display none -monitor none -serial stdio \
    -kernel "$elf" >"$log" 2>&1
cat "$log" | head -20
status=0
need() {
    if ! grep -q -- "$1" "$log"; then
        echo "qemu_boot: missing console line: $1"
        status=1
    fi
}
need "matekf405wing: clock HSE never ready: HSI 16 MHz"
need "params: store corrupt: defaults"
need "servos: S1..S8 on TIM4/TIM3/TIM8/TIM12, 50 Hz, start pulse 0 us"
need "imu: missing on SPI1"
need "baro: missing on I2C1"
need "pitot: missing on I2C2"
need "gps: missing on USART3"
need "rc: receiver missing"
need "failsafe: sensors (no IMU samples)"
beats=$(grep -c '^hb ticks ' "$log")
if [ "$beats" -lt 3 ]; then
    echo "qemu_boot: $beats heartbeats (want >= 3): the loop stopped"
    status=1
fi
first=$(grep '^hb ticks ' "$log" | head -1 | awk '{print $3}')
last=$(grep '^hb ticks ' "$log" | tail -1 | awk '{print $3}')
if [ -z "$first" ] || [ "$last" -le "$first" ]; then
    echo "qemu_boot: tick count not rising ($first -> $last)"
    status=1
fi
if ! grep '^hb ticks ' "$log" | tail -1 | grep -Eq 'fs 2 .*servo_us 1500 1500 1000 1500 '; then
    echo "qemu_boot: servos not at their failsafe pulses:"
    grep '^hb ticks ' "$log" | tail -1
    status=1
fi
[ "$status" = 0 ] && echo "qemu_boot: OK ($beats heartbeats, ticks $first -> $last)"
exit $status
