# Cross-compiling for 64-bit ARM Linux on a Debian x86-64 host (./dev arm64):
# Debian's g++-aarch64-linux-gnu, the dependencies' arm64 packages beside
# the host's (multiarch: /usr/lib/aarch64-linux-gnu), the header-only ones
# shared, and the tests run under qemu-user.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
# CMake finds packages under /usr/lib/aarch64-linux-gnu/cmake and the
# architecture-independent /usr/share and /usr/lib/cmake; never the host's
# x86-64 libraries.
set(CMAKE_IGNORE_PATH /usr/lib/x86_64-linux-gnu /usr/lib/x86_64-linux-gnu/cmake)
# pkg-config (GMP) reads the arm64 .pc files alone.
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig)
# ctest (and gtest_discover_tests) run the test programs through qemu, with
# the loader and C library of the arm64 packages (libc6:arm64, under /), not
# the cross toolchain's root (/usr/aarch64-linux-gnu): its loader beside
# libc6:arm64's libc.so.6, another Debian revision of glibc 2.36 whose
# private layout differs, made the first pthread_create loop for ever.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64;-L;/)
