// The passes of the report's lighting model and the layers a film accumulates: their order, their names (shared by
// the command line, the view files and the panel), and the report's weights. What every part of a render agrees on
// before anything is traced; the settings of the estimators that fill them are in render_settings.h.
// This folder, passes/, is the vocabulary of a render: depends on the standard library only.
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace lueur {

/// The report's lighting passes, and Lueur's `ln`: the light of the second and later bounces after the pixel's
/// surface, every path that L1 and L2 leave out, up to the bounce limit. The image is the sum over enabled passes of
/// weight x average(pass).
enum class Pass : int { kLe = 0, kL1 = 1, kL2 = 2, kAo = 3, kLn = 4 };
inline constexpr int kPassCount = 5;
inline constexpr std::array<std::string_view, kPassCount> kPassNames = {"le", "l1", "l2", "ao", "ln"};

/// What the film accumulates: the passes, then the layers that explain L2's reuse: the parts of L2 whose L1(q)
/// came from the screen (report figure 7), was traced anew (figure 8) or came from the L1 store, and where L2's bounce
/// hits took L1(q) from (red: the screen, green: the store, blue: recomputed, as shares of the hits).
/// `l1-diffuse` is the view-independent part of L1, kept when L2 reuses its running average diffuse-only.
/// `cache-cells` shows the L1 store's cells at the primary hits, each in its own hashed colour.
enum class Layer : int {
  kLe = 0,
  kL1,
  kL2,
  kAo,
  kLn,
  kL2Reused,
  kL2Recomputed,
  kReuseFraction,
  kL1Diffuse,
  kL2Cached,
  kCacheCells
};
inline constexpr int kLayerCount = 11;
inline constexpr std::array<std::string_view, kLayerCount> kLayerNames = {
    "le", "l1", "l2", "ao", "ln", "l2-reused", "l2-recomputed", "reuse-fraction", "l1-diffuse", "l2-cached",
    "cache-cells"};
inline constexpr Layer layer_of(Pass p) { return static_cast<Layer>(static_cast<int>(p)); }

/// Finds `name` in a name table; nullopt when it is not there.
template <typename Enum, size_t N>
std::optional<Enum> enum_from_name(const std::array<std::string_view, N>& names, std::string_view name) {
  for (size_t i = 0; i < N; ++i)
    if (names[i] == name) return static_cast<Enum>(i);
  return std::nullopt;
}
template <typename Enum, size_t N>
std::string_view enum_name(const std::array<std::string_view, N>& names, Enum value) {
  return names[static_cast<size_t>(value)];
}

/// The report's pass weights: Le 1, L1 0.6, L2 0.4, AO 1 (and the further bounces, which the report has not, 1).
inline constexpr std::array<float, kPassCount> kReportWeights = {1.0f, 0.6f, 0.4f, 1.0f, 1.0f};
/// The physical weights: every pass at 1, so that Le + L1 + L2 + ln is the full solution (AO is no light: the
/// physical preset turns it off).
inline constexpr std::array<float, kPassCount> kPhysicalWeights = {1.0f, 1.0f, 1.0f, 1.0f, 1.0f};

}  // namespace lueur
