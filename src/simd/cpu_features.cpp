#include "simd/cpu_features.h"

#include <cpuid.h>
#include <cstdint>
#include <cstring>

namespace wideray {
namespace {

struct CpuFeatures {
    bool sse42 = false, avx2 = false, avx512 = false;
};

uint64_t xgetbv0() {
    uint32_t eax, edx;
    __asm__ volatile("xgetbv" : "=a"(eax), "=d"(edx) : "c"(0));
    return (uint64_t(edx) << 32) | eax;
}

CpuFeatures detect() {
    CpuFeatures f;
    unsigned a, b, c, d;
    if (!__get_cpuid(1, &a, &b, &c, &d)) return f;
    f.sse42 = (c & bit_SSE4_2) != 0;
    bool osxsave = (c & bit_OSXSAVE) != 0;
    bool avx = (c & bit_AVX) != 0, fma = (c & bit_FMA) != 0;
    uint64_t xcr0 = osxsave ? xgetbv0() : 0;
    bool osAvx = (xcr0 & 0x6) == 0x6;            // SSE and AVX state
    bool osAvx512 = (xcr0 & 0xE6) == 0xE6;       // plus opmask and the upper ZMM registers
    if (!__get_cpuid_count(7, 0, &a, &b, &c, &d)) return f;
    bool avx2 = (b & bit_AVX2) != 0, bmi1 = (b & bit_BMI) != 0, bmi2 = (b & bit_BMI2) != 0;
    bool avx512 = (b & bit_AVX512F) && (b & bit_AVX512VL) && (b & bit_AVX512BW) && (b & bit_AVX512DQ);
    f.avx2 = f.sse42 && osAvx && avx && fma && avx2 && bmi1 && bmi2;
    f.avx512 = f.avx2 && osAvx512 && avx512;
    return f;
}

const CpuFeatures& features() {
    static const CpuFeatures f = detect();
    return f;
}

} // namespace

const char* isaName(Isa isa) {
    switch (isa) {
    case Isa::Sse42: return "sse42";
    case Isa::Avx2: return "avx2";
    case Isa::Avx512: return "avx512";
    }
    return "?";
}

std::optional<Isa> parseIsa(std::string_view name) {
    for (Isa isa : {Isa::Sse42, Isa::Avx2, Isa::Avx512})
        if (name == isaName(isa)) return isa;
    return std::nullopt;
}

bool cpuSupports(Isa isa) {
    switch (isa) {
    case Isa::Sse42: return features().sse42;
    case Isa::Avx2: return features().avx2;
    case Isa::Avx512: return features().avx512;
    }
    return false;
}

Isa bestIsa() {
    if (cpuSupports(Isa::Avx512)) return Isa::Avx512;
    if (cpuSupports(Isa::Avx2)) return Isa::Avx2;
    return Isa::Sse42;
}

std::vector<Isa> supportedIsas() {
    std::vector<Isa> isas;
    for (Isa isa : {Isa::Sse42, Isa::Avx2, Isa::Avx512})
        if (cpuSupports(isa)) isas.push_back(isa);
    return isas;
}

std::string cpuModelName() {
    unsigned regs[12];
    unsigned a, b, c, d;
    if (!__get_cpuid(0x80000000, &a, &b, &c, &d) || a < 0x80000004) return "unknown x86-64";
    for (unsigned i = 0; i < 3; ++i) __get_cpuid(0x80000002 + i, &regs[4 * i], &regs[4 * i + 1], &regs[4 * i + 2], &regs[4 * i + 3]);
    char name[49] = {};
    std::memcpy(name, regs, 48);
    std::string s(name);
    size_t first = s.find_first_not_of(' ');
    return first == std::string::npos ? "unknown x86-64" : s.substr(first);
}

} // namespace wideray
