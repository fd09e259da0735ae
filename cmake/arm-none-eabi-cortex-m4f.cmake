# SPDX-License-Identifier: Apache-2.0
# Toolchain file: ARM Cortex-M4F (hard float, single-precision FPU), bare metal, newlib-nano.
# Facts checked in ../shared/TOOLCHAIN.md. -fno-math-errno lets sqrtf compile to vsqrt.f32.
# -ffp-contract=fast: FPv4-SP has VFMA, so a·b + c becomes one fused multiply-add (one
# instruction, one rounding) in every file built for the target; -std=c11 would otherwise turn
# contraction off. The float results then differ from the host-float build (which keeps it
# off) at rounding level only.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar)
set(CMAKE_RANLIB arm-none-eabi-ranlib)
set(CMAKE_OBJCOPY arm-none-eabi-objcopy)
set(CMAKE_SIZE arm-none-eabi-size)
set(CMAKE_NM arm-none-eabi-nm)

set(UVMS_M4F_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard -ffunction-sections -fdata-sections -fno-math-errno -ffp-contract=fast")
set(CMAKE_C_FLAGS_INIT "${UVMS_M4F_FLAGS}")
set(CMAKE_ASM_FLAGS_INIT "${UVMS_M4F_FLAGS}")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)

# Cross-compiled test images run on an emulated Cortex-M4F board (MPS2 AN386) via semihosting;
# QEMU passes the image's exit(n) back as its exit code, so ctest can run them.
set(CMAKE_CROSSCOMPILING_EMULATOR
    qemu-system-arm;-M;mps2-an386;-nographic;-monitor;none;-serial;none;-semihosting-config;enable=on,target=native;-kernel)
