# CMake toolchain file: cross-compile impulse for 64-bit Arm Linux with Debian's
# g++-aarch64-linux-gnu, for the determinism matrix (scripts/determinism-matrix),
# which runs the result under qemu-aarch64.
#
#   cmake -S . -B build-matrix/aarch64-O2 \
#         -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
#         -DIMPULSE_WITH_BOX2D=OFF -DIMPULSE_WITH_TESTS=OFF
#
# Libraries come from the cross sysroot /usr/aarch64-linux-gnu only. Headers and
# CMake package configs are searched there AND on the host: Eigen and nlohmann-json
# are header-only and architecture-independent, installed once in /usr/include with
# their configs in /usr/share/eigen3/cmake and /usr/share/cmake/nlohmann_json.
# (Debian's cross g++ already searches /usr/include after its own sysroot headers,
# so the host's C and C++ library headers never shadow the aarch64 ones.)

set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(IMPULSE_AARCH64_TRIPLE aarch64-linux-gnu)
set(CMAKE_C_COMPILER ${IMPULSE_AARCH64_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${IMPULSE_AARCH64_TRIPLE}-g++)

set(CMAKE_FIND_ROOT_PATH /usr/${IMPULSE_AARCH64_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)  # build tools run on the host
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)   # never link a host (x86-64) library
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

# A static executable runs under plain `qemu-aarch64 BINARY`, with no dynamic
# loader or shared libraries to find.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static")

# For anything CMake itself runs (try_run, add_test): -L also covers dynamic binaries.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/${IMPULSE_AARCH64_TRIPLE})
