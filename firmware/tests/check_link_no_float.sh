#!/bin/sh
# check_link_no_float.sh GCC NM OUT_DIR SOURCE_DIR GENERATED_DIR - the
# MAVLink link (firmware/link/fw_link*.c) and the step it rides on, compiled for a
# Cortex-M0 with soft float (-Os, as an image is), reference no soft-float
# routine: MAVLink's float fields are bit patterns made with integers
# (src/math/f32_bits.c). tools/image/check_no_float.sh does the inspection.
set -eu
gcc="$1"
nm="$2"
out="$3"
src="$4"
gen="$5"
mkdir -p "$out"
objs=""
for c in "$src"/firmware/link/fw_link*.c "$src"/firmware/fw_step.c; do
    o="$out/$(basename "$c" .c).o"
    "$gcc" -mcpu=cortex-m0 -mthumb -mfloat-abi=soft -Os -std=c11 \
        -DMAVLINK_NO_CONVERSION_HELPERS -DMAVLINK_NO_SIGN_PACKET -DMAVLINK_NO_SIGNATURE_CHECK \
        -I"$src/firmware" -I"$src/include" -isystem "$gen" -c "$c" -o "$o"
    objs="$objs $o"
done
# shellcheck disable=SC2086 # one word per object
exec "$src/tools/image/check_no_float.sh" "$nm" $objs
