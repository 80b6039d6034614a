#pragma once
// Where an animated scene's camera is at each frame.
#include "core/scene.h"

namespace wideray {

/// The camera of `animation` at `frame`. Position, look_at and up follow a cubic Hermite spline through
/// the keys, with Catmull-Rom tangents taken over frame numbers (keys at uneven frame spacing are passed
/// without a jump in speed); fov, aperture and focus distance are linear between keys; the shutter is
/// the earlier key's. Each key is met exactly at its frame; before the first key and after the last
/// the camera holds still.
Camera cameraAtFrame(const Animation& animation, int frame);

} // namespace wideray
