// The avx512 kernels: the shared kernel source compiled with avx512 flags (see src/CMakeLists.txt).
#define WIDERAY_ISA avx512
#define WIDERAY_ISA_TABLE avx512KernelTable
#include "kernels/isa_kernels.inl"
