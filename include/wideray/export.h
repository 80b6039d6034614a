#pragma once
/// WIDERAY_API marks what the shared library exports; everything else in it is hidden.
#if defined(_WIN32)
#define WIDERAY_API
#else
#define WIDERAY_API __attribute__((visibility("default")))
#endif
