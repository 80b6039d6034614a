// The sse42 kernels: the shared kernel source compiled with sse42 flags (see src/CMakeLists.txt).
#define WIDERAY_ISA sse42
#define WIDERAY_ISA_TABLE sse42KernelTable
#include "kernels/isa_kernels.inl"
