# Cross compiling for bare-metal Cortex-M with the GNU Arm toolchain
# (Debian/Ubuntu package gcc-arm-none-eabi + libnewlib-arm-none-eabi).
#
# HT_ARM_CPU picks the core: cortex-m0 (ARMv6-M: Thumb-1, no hardware divide),
# cortex-m3 (ARMv7-M), cortex-m4 (ARMv7E-M). Everything is built soft-float:
# the library is integer only, and the float ABI must then not matter.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(HT_ARM_CPU "cortex-m4" CACHE STRING "Cortex-M core: cortex-m0, cortex-m3 or cortex-m4")
set_property(CACHE HT_ARM_CPU PROPERTY STRINGS cortex-m0 cortex-m3 cortex-m4)
# try_compile runs this file again in a fresh project: pass the choice on.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES HT_ARM_CPU)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar CACHE FILEPATH "")
set(CMAKE_RANLIB arm-none-eabi-ranlib CACHE FILEPATH "")
set(CMAKE_SIZE arm-none-eabi-size CACHE FILEPATH "")
set(CMAKE_NM arm-none-eabi-nm CACHE FILEPATH "")
set(CMAKE_OBJCOPY arm-none-eabi-objcopy CACHE FILEPATH "")

# No host executables can be linked without a board's startup code and
# linker script, so probe the compiler with a static library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# -ffunction/-fdata-sections let --gc-sections drop what the image never
# calls; -fstack-usage writes a .su file per object (worst frame of each
# function), -fcallgraph-info=su a .ci call graph for the whole-path check.
set(CMAKE_C_FLAGS_INIT
    "-mcpu=${HT_ARM_CPU} -mthumb -mfloat-abi=soft -ffunction-sections -fdata-sections -fstack-usage -fcallgraph-info=su")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
