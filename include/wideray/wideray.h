#pragma once
/// The whole public API: #include <wideray/wideray.h> and link wideray::wideray (docs/library.md).
#include "wideray/error.h"
#include "wideray/mesh_file.h"
#include "wideray/options.h"
#include "wideray/ray.h"
#include "wideray/render.h"
#include "wideray/scene.h"
#include "wideray/version.h"
