// Which acceleration structure traces the rays, and its names for the command line, view files and the panel.
// Depends on nothing: the settings, the renderer and the back-ends all name it.
#pragma once

#include <array>
#include <string_view>

namespace lueur {

/// Lueur's own BVH, or Embree (when the build has it).
enum class AccelKind : int { kLueur = 0, kEmbree = 1 };
inline constexpr std::array<std::string_view, 2> kAccelKindNames = {"lueur", "embree"};

}  // namespace lueur
