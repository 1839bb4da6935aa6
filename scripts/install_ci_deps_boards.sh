#!/usr/bin/env bash
# The board layer's CI dependencies: the GNU Arm bare-metal compiler and
# newlib (the firmware image links newlib-nano's memcpy/memset).
# --no-install-recommends keeps it near 100 MB (no documentation, no gdb).
set -euo pipefail
SUDO=""
if [ "$(id -u)" != 0 ]; then
    SUDO=sudo
fi
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends gcc-arm-none-eabi libnewlib-arm-none-eabi
arm-none-eabi-gcc --version | head -1
