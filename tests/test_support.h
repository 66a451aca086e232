// Helpers shared by the test suites: temporary directories, running the lueur executable, file reading, scoped
// environment variables, waiting for events.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lueur::test {

/// A fresh empty directory under the system temp dir (emptied first if a previous run left it), removed once the
/// executable's tests have all passed (kept, and named on stderr, when one failed).
std::string make_temp_dir(const std::string& tag);

struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `lueur` (the built executable) with the given argument string through the shell, under `timeout` so
/// that a hang fails the test (exit code 124) instead of stalling the suite. `prefix` goes before the command:
/// environment variables ("LUEUR_MEMORY_LIMIT_MB=64") or a wrapper command.
CommandResult run_lueur(const std::string& arguments, const std::string& prefix = "");

/// Single-quotes a string for the shell (quotes inside it included).
std::string shell_quote(const std::string& text);

/// Runs any executable the same way (e.g. lueur-bench).
CommandResult run_program(const std::string& executable, const std::string& arguments, const std::string& prefix = "");

std::string read_file(const std::string& path);
bool file_exists(const std::string& path);

/// Path of ../shared/scenes/<relative>; empty when the shared scenes are not beside this checkout.
std::string shared_scene(const std::string& relative);

/// Sets an environment variable for one scope, then puts back what was there before (the old value, or no
/// variable) on every way out of the scope: a failed ASSERT returns early, and the tests after it in the same
/// process must not inherit the setting.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value);
  ~ScopedEnv();
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_;
  std::optional<std::string> previous_;
};

/// How long a test waits for an event before it gives up. Only there so that a hang fails instead of stalling
/// the suite: far beyond any healthy run on a loaded machine or under sanitizers, never a bound on speed.
inline constexpr double kGiveUpSeconds = 120.0;

/// Polls `condition` every `poll_seconds` until it holds (true) or `timeout_seconds` pass (false): for waiting on
/// an event the code under test gives no signal for. The timeout only keeps a hang from stalling the suite.
bool wait_until(const std::function<bool()>& condition, double timeout_seconds = kGiveUpSeconds,
                double poll_seconds = 0.001);

}  // namespace lueur::test

#include <gtest/gtest.h>

#include "passes/render_settings.h"
#include "integrator/traced_scene.h"
#include "scene/scene.h"

namespace lueur::test {

/// An axis-aligned box [-half, half]^3 whose 12 inward-facing triangles all emit `le` and reflect `rho`
/// (no Ks, so K = 1 makes them Lambertian). L1 = rho Le and L2 = rho^2 Le everywhere inside.
Scene make_closed_emitting_box(float half, Vec3 rho, Vec3 le);

/// A closed UV sphere (segments x rings) of radius r around the origin, every triangle facing inwards, emitting
/// `le` with albedo `rho`. Inside a sphere cos cos / d^2 is constant, so the area-sampled estimators have small,
/// bounded variance: the closed forms L1 = rho Le and L2 = rho^2 Le can be checked tightly everywhere.
Scene make_closed_emitting_sphere(float r, int segments, int rings, Vec3 rho, Vec3 le);

/// A w x h rectangle light (two triangles, facing -y) at height `height` above a large diffuse floor at y = 0.
Scene make_rect_light_over_floor(float w, float h, float height, Vec3 rho, Vec3 le);

/// The surface point that a ray straight down from `height` above `point` meets first; nullopt when it meets none.
std::optional<SurfacePoint> surface_below(const TracedScene& traced, const Vec3& point, float height);

/// Irradiance at `p`, on a surface with unit normal `n`, from a planar polygon of uniform radiance `le`: Lambert's
/// formula (1760), E = le / 2 * sum_i theta_i (gamma_i . n), where edge i runs from corner i to corner i + 1,
/// theta_i is the angle it subtends at p and gamma_i is the unit normal of the plane through p and that edge.
/// The corners run counter-clockwise seen from the emitting side (Lueur's winding: (c1 - c0) x (c2 - c0) points
/// there); from behind, p sees the back, which does not emit, and gets 0. The formula needs the polygon wholly
/// above p's horizon: when a corner lies below it the result is NaN, so such a test fails instead of passing.
double lambert_irradiance(const std::vector<glm::dvec3>& polygon, const glm::dvec3& p, const glm::dvec3& n, double le);

/// Wilson-Hilferty: true when the chi-square statistic is implausibly large for `dof` degrees of freedom
/// (beyond about 4 standard deviations, p < 1e-4).
bool chi_square_rejects(double statistic, int dof);

/// Names parameterised tests after the light strategy they run ("all", "uniform", ...).
std::string strategy_test_name(const ::testing::TestParamInfo<LightStrategy>& info);

}  // namespace lueur::test
