// The avx2 kernels of the course's structures: the shared source compiled with avx2 flags (see
// src/CMakeLists.txt).
#define WIDERAY_ISA avx2
#define WIDERAY_ISA_COURSE_KERNELS avx2CourseKernels
#include "kernels/isa_course_kernels.inl"
