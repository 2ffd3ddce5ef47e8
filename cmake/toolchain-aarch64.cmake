# Cross build for aarch64 Linux boards (Raspberry Pi CM4, the emulated QEMU
# virt board) with Debian's cross compiler (g++-aarch64-linux-gnu) and
# multiarch libraries (libgpiod-dev:arm64). Header-only packages (Eigen,
# CLI11, toml++) come from the build machine's /usr/include.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
# Multiarch: arm64 libraries live in /usr/lib/aarch64-linux-gnu, outside the
# root path; the library architecture keeps x86-64 ones out of the search.
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

# No fused multiply-add contraction: the board rounds as the x86-64 host
# does, so a run on the board can be compared with the host's simulation.
set(CMAKE_C_FLAGS_INIT "-ffp-contract=off")
set(CMAKE_CXX_FLAGS_INIT "-ffp-contract=off")
