#include "wideray/version.h"

#include "simd/cpu_features.h"

namespace wideray {

const char* version() { return WIDERAY_VERSION_STRING; }

const char* bestIsaName() { return isaName(bestIsa()); }

} // namespace wideray
