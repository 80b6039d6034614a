// The avx512 kernels of the course's structures: the shared source compiled with avx512 flags (see
// src/CMakeLists.txt).
#define WIDERAY_ISA avx512
#define WIDERAY_ISA_COURSE_KERNELS avx512CourseKernels
#include "kernels/isa_course_kernels.inl"
