// The head-light: a small emitter just behind the camera, facing where it looks, that L1 samples besides the
// scene's emitters (one point on it per L1 sample), so that whatever the camera sees is lit, inside a closed room
// too. It moves with the camera and no ray can hit it (it is not in the acceleration structure). Depends on the
// camera and the light table's record.
#pragma once

#include "core/camera.h"
#include "lights/light_sampler.h"

namespace lueur {

/// The head-light of `camera` in a scene of bounding-box diagonal `diagonal`: a triangle of circumradius 3% of the
/// diagonal, 2% of the diagonal behind the eye, facing `camera.forward`, with the radiance that makes a white surface
/// straight ahead at half the diagonal read `scale` (E = pi scale there, in the small-light limit).
EmitterRecord make_camera_light(const Camera& camera, float diagonal, float scale = 1.0f);

}  // namespace lueur
