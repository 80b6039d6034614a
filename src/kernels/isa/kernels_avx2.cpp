// The avx2 kernels: the shared kernel source compiled with avx2 flags (see src/CMakeLists.txt).
#define WIDERAY_ISA avx2
#define WIDERAY_ISA_TABLE avx2KernelTable
#include "kernels/isa_kernels.inl"
