# Cross-building for the robot: 32-bit x86 for a Geode (no CMOV, no SSE),
# with Debian's gcc-multilib. bscript_add_behavior then compiles behaviors
# with `bsc -target i586` and links the robot's runtime shim.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR i586)
set(CMAKE_C_COMPILER gcc)
set(CMAKE_CXX_COMPILER g++)
set(CMAKE_C_FLAGS_INIT "-m32 -march=i586 -mtune=geode")
set(CMAKE_CXX_FLAGS_INIT "-m32 -march=i586 -mtune=geode")
