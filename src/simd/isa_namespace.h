#pragma once
// Kernel code is compiled once per ISA. Everything in the kernel and SIMD headers lives in an inline
// namespace named after the ISA of the translation unit (set by its WIDERAY_ISA definition), so
// that an inline function compiled with AVX flags can never be linked into baseline code.
#ifndef WIDERAY_ISA
#define WIDERAY_ISA baseline
#endif
