// The sse42 kernels of the course's structures: the shared source compiled with sse42 flags (see
// src/CMakeLists.txt).
#define WIDERAY_ISA sse42
#define WIDERAY_ISA_COURSE_KERNELS sse42CourseKernels
#include "kernels/isa_course_kernels.inl"
