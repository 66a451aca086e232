// What a shadow ray needs of one emitter, and the answer of a light choice. Depends on core/math.h only.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace lueur {

/// What a shadow ray needs of one emitter, in one place: its corners, unit normal, emission and area, so that
/// sampling a point on it reads one record instead of the scene's triangle, vertex and material arrays.
struct EmitterRecord {
  Vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};
  Vec3 normal{0.0f};  ///< unit geometric normal: the side it shines on
  Vec3 ke{0.0f};
  float area = 0.0f;
};

/// An emitter's weight among the scene's when choosing by power: area x luminance(Ke), in double so that absurd Ke
/// stays finite.
inline double emitter_power(const EmitterRecord& e) { return static_cast<double>(e.area) * luminance(e.ke); }

struct LightChoice {
  uint32_t index = 0;  ///< position in the light table
  float pmf = 0.0f;    ///< probability of choosing it; 0: no emitter can light the point (no shadow ray)
};

}  // namespace lueur
