#pragma once
// CPU feature detection (CPUID and XGETBV, so that the OS's support for the AVX and AVX-512 register
// state counts too). Compiled with baseline flags.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace wideray {

enum class Isa { Sse42 = 0, Avx2 = 1, Avx512 = 2 };

const char* isaName(Isa isa);
std::optional<Isa> parseIsa(std::string_view name);  ///< "sse42", "avx2", "avx512"

/// Whether this CPU and OS can run code compiled for the ISA (AVX2 means AVX2 + FMA + BMI;
/// AVX-512 means F, VL, BW and DQ).
bool cpuSupports(Isa isa);
Isa bestIsa();
/// Every ISA this CPU and OS run, from the baseline up.
std::vector<Isa> supportedIsas();
std::string cpuModelName();

} // namespace wideray
