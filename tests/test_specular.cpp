// Mirrors and glass: the dielectric's Fresnel reflectance and its sampling against the formula, total internal
// reflection, reciprocity and energy conservation of every BSDF; and, rendered, a mirror and a glass slab against
// their closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "integrator/brdf.h"
#include "integrator/renderer.h"
#include "integrator/specular.h"
#include "test_support.h"

namespace lueur {
namespace {

Material glass(float ior, Vec3 tf = Vec3(1.0f), Vec3 kd = Vec3(0.0f)) {
  Material m;
  m.surface = SurfaceKind::kGlass;
  m.ior = ior;
  m.tf = tf;
  m.kd = kd;
  return m;
}

Material mirror(Vec3 ks, Vec3 kd = Vec3(0.0f)) {
  Material m;
  m.surface = SurfaceKind::kMirror;
  m.ks = ks;
  m.kd = kd;
  return m;
}

/// A unit direction at angle `theta` from +z in the xz plane.
Vec3 at_angle(float theta) { return Vec3(std::sin(theta), 0.0f, std::cos(theta)); }

TEST(Fresnel, NormalIncidenceIsTheSquaredIndexRatio) {
  for (const float n : {1.33f, 1.5f, 2.5f}) {
    const float r = (n - 1.0f) / (n + 1.0f);
    EXPECT_NEAR(fresnel_dielectric(1.0f, n), r * r, 1e-6f) << n;
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f / n), r * r, 1e-6f) << n;  // from inside, the same
  }
  EXPECT_NEAR(fresnel_dielectric(0.0f, 1.5f), 1.0f, 1e-6f);  // grazing: all reflected
  EXPECT_NEAR(fresnel_dielectric(0.7f, 1.0f), 0.0f, 1e-7f);  // no boundary: nothing reflected
}

TEST(Fresnel, IsReciprocalAcrossTheBoundary) {
  // Light refracted from angle i to t reflects as much going either way: F(i, n) = F(t, 1 / n).
  for (const float n : {1.33f, 1.5f, 2.5f})
    for (int k = 0; k < 20; ++k) {
      const float cos_i = 0.025f + 0.05f * static_cast<float>(k);
      const float sin_t = std::sqrt(1.0f - cos_i * cos_i) / n;
      const float cos_t = std::sqrt(1.0f - sin_t * sin_t);
      // Within float rounding: cos_t loses digits near the critical angle.
      EXPECT_NEAR(fresnel_dielectric(cos_i, n), fresnel_dielectric(cos_t, 1.0f / n), 1e-4f) << n << " " << cos_i;
    }
}

TEST(Fresnel, BeyondTheCriticalAngleEveryRayInsideGlassIsReflectedWhole) {
  const Material m = glass(1.5f, Vec3(0.2f, 0.5f, 0.9f));  // the filter tints transmission, not reflection
  const float critical = std::asin(1.0f / 1.5f);
  const Vec3 n(0.0f, 0.0f, 1.0f);
  for (const float beyond : {0.01f, 0.2f, 0.6f}) {
    const Vec3 wo = at_angle(critical + beyond);
    Vec3 wt(0.0f);
    EXPECT_FALSE(refract(wo, n, 1.0f / 1.5f, wt));
    for (const float u : {0.0f, 0.3f, 0.999f}) {
      const SpecularSample s = sample_specular(m, Vec3(0.0f), n, n, wo, /*entering=*/false, u);
      ASSERT_EQ(s.lobe, SpecularLobe::kReflect);
      EXPECT_EQ(s.weight, Vec3(1.0f));
      EXPECT_NEAR(glm::dot(s.dir, reflect(wo, n)), 1.0f, 1e-6f);
    }
  }
  // Just inside the critical angle, some light leaves.
  EXPECT_LT(fresnel_dielectric(std::cos(critical - 0.05f), 1.0f / 1.5f), 1.0f);
}

TEST(Fresnel, RefractionFollowsSnellsLaw) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  for (const float eta : {1.33f, 1.5f, 1.0f / 1.5f}) {
    const Vec3 wo = at_angle(0.4f);
    Vec3 wt(0.0f);
    ASSERT_TRUE(refract(wo, n, eta, wt));
    EXPECT_NEAR(glm::length(wt), 1.0f, 1e-6f);
    EXPECT_LT(wt.z, 0.0f);                                    // on the other side
    EXPECT_NEAR(std::sin(0.4f), eta * std::abs(wt.x), 1e-5f);  // n_i sin i = n_t sin t
    EXPECT_LT(wt.x, 0.0f);                                    // in the plane of incidence, across the normal
  }
}

TEST(DielectricSampling, ChoosesReflectionWithTheFresnelProbability) {
  // Chi-square of the reflected and transmitted counts against F and 1 - F, at angles from normal to grazing, from
  // both sides of the boundary.
  const Material m = glass(1.5f);
  const Vec3 n(0.0f, 0.0f, 1.0f);
  Pcg32 rng(7, 11);
  const int samples = 40000;
  for (const bool entering : {true, false})
    for (const float theta : {0.0f, 0.5f, 0.7f, 1.2f, 1.5f}) {
      const Vec3 wo = at_angle(theta);
      const float f = fresnel_dielectric(wo.z, entering ? 1.5f : 1.0f / 1.5f);
      int reflected = 0, transmitted = 0;
      for (int k = 0; k < samples; ++k) {
        const SpecularSample s = sample_specular(m, Vec3(0.0f), n, n, wo, entering, rng.next_float());
        ASSERT_NE(s.lobe, SpecularLobe::kNone);
        ASSERT_NE(s.lobe, SpecularLobe::kBase);
        (s.lobe == SpecularLobe::kReflect ? reflected : transmitted)++;
        EXPECT_EQ(s.weight, Vec3(1.0f));  // F / F and (1 - F) / (1 - F): every sample carries all the light
      }
      if (f >= 1.0f) {
        EXPECT_EQ(transmitted, 0);
        continue;
      }
      const double expected_r = samples * static_cast<double>(f), expected_t = samples - expected_r;
      const double chi2 = (reflected - expected_r) * (reflected - expected_r) / expected_r +
                          (transmitted - expected_t) * (transmitted - expected_t) / expected_t;
      EXPECT_FALSE(test::chi_square_rejects(chi2, 1)) << "theta " << theta << " entering " << entering << ": F "
                                                     << f << ", reflected " << reflected << " of " << samples;
    }
}

TEST(SpecularParts, NeverReflectMoreThanArrives) {
  for (const Vec3 kd : {Vec3(0.0f), Vec3(0.3f), Vec3(0.9f, 0.1f, 0.5f), Vec3(1.0f)})
    for (const Vec3 ks : {Vec3(0.0f), Vec3(0.5f), Vec3(0.95f), Vec3(1.0f, 0.2f, 0.7f)}) {
      for (const Material& m : {mirror(ks, kd), glass(1.5f, ks, kd)}) {
        const SpecularParts parts = specular_parts(m, kd);
        for (int c = 0; c < 3; ++c) {
          EXPECT_GE(parts.base[c], 0.0f);
          EXPECT_LE(parts.base[c] + parts.specular[c], 1.0f + 1e-6f);
        }
        // What one sampled scattering carries, averaged over the lobe choice: at most what arrived.
        const Vec3 n(0.0f, 0.0f, 1.0f), wo = at_angle(0.3f);
        Vec3 mean(0.0f);
        const int count = 4096;
        for (int k = 0; k < count; ++k) {
          const SpecularSample s = sample_specular(m, kd, n, n, wo, true, (k + 0.5f) / count);
          mean += s.weight / static_cast<float>(count);
        }
        for (int c = 0; c < 3; ++c) EXPECT_LE(mean[c], 1.0f + 1e-3f);
      }
    }
  // A mirror whose Kd + Ks passes 1 keeps their proportion.
  const SpecularParts parts = specular_parts(mirror(Vec3(0.8f), Vec3(0.4f)), Vec3(0.4f));
  EXPECT_NEAR(parts.base.r, 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(parts.specular.r, 2.0f / 3.0f, 1e-6f);
}

/// The albedo of a BRDF toward `wo`: the integral of f cos over the hemisphere, by stratified uniform directions.
double albedo(const Material& m, const Vec3& kd, const Vec3& wo, float blinn_k) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  const int side = 400;
  double sum = 0.0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const float z = (static_cast<float>(i) + 0.5f) / side, phi = 2.0f * kPi * (static_cast<float>(j) + 0.5f) / side;
      const float r = std::sqrt(1.0f - z * z);
      const Vec3 wi(r * std::cos(phi), r * std::sin(phi), z);
      sum += static_cast<double>(eval_brdf(m, kd, n, wi, wo, blinn_k).r * z);
    }
  return sum * 2.0 * kPi / (side * side);
}

TEST(Brdf, IsReciprocal) {
  Material glossy;
  glossy.kd = Vec3(0.4f);
  glossy.ks = Vec3(0.5f);
  glossy.ns = 32.0f;
  Material mix;
  mix.kd = Vec3(0.7f);
  mix.ns = 10.0f;
  const Vec3 n(0.0f, 0.0f, 1.0f);
  Pcg32 rng(3, 5);
  for (const Material& m : {glossy, mix, mirror(Vec3(0.5f), Vec3(0.3f)), glass(1.5f, Vec3(1.0f), Vec3(0.2f))})
    for (int k = 0; k < 200; ++k) {
      const float u1 = rng.next_float(), u2 = rng.next_float(), u3 = rng.next_float(), u4 = rng.next_float();
      const Vec3 a(std::sqrt(1 - u1 * u1) * std::cos(6.283f * u2), std::sqrt(1 - u1 * u1) * std::sin(6.283f * u2), u1);
      const Vec3 b(std::sqrt(1 - u3 * u3) * std::cos(6.283f * u4), std::sqrt(1 - u3 * u3) * std::sin(6.283f * u4), u3);
      const Vec3 ab = eval_brdf(m, m.kd, n, a, b, 0.7f), ba = eval_brdf(m, m.kd, n, b, a, 0.7f);
      EXPECT_NEAR(ab.r, ba.r, 1e-5f * std::max(1.0f, ab.r));
    }
}

TEST(Brdf, ConservesEnergy) {
  const Vec3 n(0.0f, 0.0f, 1.0f);
  Material lambert;
  lambert.kd = Vec3(1.0f);
  Material report_mix;  // no Ks, no Ns: K Lambert + (1 - K) the lobe of exponent 0, itself Lambert
  report_mix.kd = Vec3(1.0f);
  for (const float theta : {0.0f, 0.6f, 1.3f}) {
    const Vec3 wo = at_angle(theta);
    EXPECT_NEAR(albedo(lambert, lambert.kd, wo, 1.0f), 1.0, 2e-3);
    EXPECT_NEAR(albedo(report_mix, report_mix.kd, wo, 0.7f), 1.0, 2e-3);
    // A mirror's or glass's base: what its parts leave it.
    EXPECT_LE(albedo(mirror(Vec3(0.6f), Vec3(0.9f)), Vec3(0.9f), wo, 0.7f), 0.9 / 1.5 + 2e-3);
    EXPECT_NEAR(albedo(glass(1.5f, Vec3(1.0f), Vec3(0.25f)), Vec3(0.25f), wo, 0.7f), 0.25, 2e-3);
    // The normalised Blinn-Phong lobe, (n + 8) / (8 pi) cos^n: kept as the report wrote it (images byte-identical
    // to before), it reflects up to 7% more than arrives at normal incidence for exponents near 10, and less
    // elsewhere. Held to that measured bound, so that a change to it cannot pass unnoticed.
    for (const float exponent : {1.0f, 10.0f, 32.0f, 80.0f, 1000.0f}) {
      Material lobe;
      lobe.kd = Vec3(0.0f);
      lobe.ks = Vec3(1.0f);
      lobe.ns = exponent;
      EXPECT_LE(albedo(lobe, lobe.kd, wo, 0.7f), 1.08) << exponent << " at " << theta;
    }
  }
}

// ---- rendered closed forms -------------------------------------------------------------------------------------

/// The mean of one layer's red channel over the image after `frames` frames.
double layer_mean(const TracedScene& traced, const CameraSpec& view, const RenderSettings& settings, Layer layer,
                  int frames) {
  Accumulation accumulation;
  accumulation.reset(settings);
  ThreadPool pool(2);
  const Camera camera = make_camera(view, settings.width, settings.height);
  for (int f = 0; f < frames; ++f) render_frame(traced, camera, settings, accumulation, pool);
  const Image image = layer_average(accumulation.film, layer);
  double sum = 0.0;
  for (size_t i = 0; i < image.rgb.size(); i += 3) sum += image.rgb[i];
  return sum / static_cast<double>(image.rgb.size() / 3);
}

/// A quad light of radiance `le` in the plane z = `z`, facing along `facing_z` (+1 or -1), 20 units wide.
void add_light(Scene& s, float z, float facing_z, float le) {
  Material light;
  light.kd = Vec3(0.0f);
  light.ke = Vec3(le);
  s.materials.push_back(light);
  const auto id = static_cast<uint32_t>(s.materials.size() - 1);
  const float h = 10.0f;
  if (facing_z > 0.0f)
    add_quad(s, Vec3(-h, -h, z), Vec3(h, -h, z), Vec3(h, h, z), Vec3(-h, h, z), id);
  else
    add_quad(s, Vec3(-h, -h, z), Vec3(-h, h, z), Vec3(h, h, z), Vec3(h, -h, z), id);
}

RenderSettings le_only(int max_bounces) {
  RenderSettings settings;
  settings.width = settings.height = 8;
  settings.enabled = {true, false, false, false, false};
  settings.max_bounces = max_bounces;
  return settings;
}

TEST(Mirror, AnEmitterSeenInAMirrorReadsKsLe) {
  const float ks = 0.8f, le = 3.0f;
  Scene s;
  s.materials.push_back(mirror(Vec3(ks)));
  add_quad(s, Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0), 0);  // facing +z, the camera
  add_light(s, 2.0f, -1.0f, le);                                                   // behind the camera, facing it
  collect_emitters(s);
  const auto traced = prepare_scene(s);
  const CameraSpec view{Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(0, 1, 0), 20.0f};
  for (const int le_rays : {1, 4}) {
    RenderSettings settings = le_only(1);  // the mirror is the one bounce
    settings.le_rays = le_rays;
    const double mean = layer_mean(*traced, view, settings, Layer::kLe, 4);
    EXPECT_NEAR(mean, ks * le, 1e-5) << le_rays << " Le rays";
  }
}

TEST(Mirror, APeriscopeOfTwoMirrorsNeedsTwoBounces) {
  // The camera looks down at a mirror that turns its rays sideways, into a second one that turns them up, into a
  // light above: two scattering events, as Cycles counts them.
  const float ks = 0.9f, le = 2.0f;
  Scene s;
  s.materials.push_back(mirror(Vec3(ks)));
  const float h = 0.5f / std::sqrt(2.0f);
  add_quad(s, Vec3(-1, -h, h), Vec3(1, -h, h), Vec3(1, h, -h), Vec3(-1, h, -h), 0);  // normal along (0, 1, 1)
  add_quad(s, Vec3(-1, 2 - 2 * h, -2 * h), Vec3(1, 2 - 2 * h, -2 * h), Vec3(1, 2 + 2 * h, 2 * h),
           Vec3(-1, 2 + 2 * h, 2 * h), 0);  // normal along (0, -1, 1)
  add_light(s, 3.0f, -1.0f, le);
  collect_emitters(s);
  const auto traced = prepare_scene(s);
  const CameraSpec view{Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(0, 1, 0), 10.0f};
  EXPECT_NEAR(layer_mean(*traced, view, le_only(2), Layer::kLe, 2), ks * ks * le, 1e-5);
  EXPECT_EQ(layer_mean(*traced, view, le_only(1), Layer::kLe, 2), 0.0);
}

TEST(Glass, AParallelSlabAtNormalIncidenceTransmitsOneMinusROverOnePlusR) {
  // Every internal reflection counted: (1 - R)^2 (1 + R^2 + R^4 + ...) = (1 - R) / (1 + R).
  const float n = 1.5f, le = 2.0f;
  Scene s;
  s.materials.push_back(glass(n));
  add_quad(s, Vec3(-5, -5, 0), Vec3(5, -5, 0), Vec3(5, 5, 0), Vec3(-5, 5, 0), 0);          // front, facing +z
  add_quad(s, Vec3(-5, -5, -0.5f), Vec3(-5, 5, -0.5f), Vec3(5, 5, -0.5f), Vec3(5, -5, -0.5f), 0);  // back, facing -z
  add_light(s, -2.0f, 1.0f, le);  // behind the slab, facing the camera
  collect_emitters(s);
  const auto traced = prepare_scene(s);
  const CameraSpec view{Vec3(0, 0, 1), Vec3(0, 0, 0), Vec3(0, 1, 0), 0.5f};  // every ray all but normal
  RenderSettings settings = le_only(64);
  settings.le_rays = 16;
  const double r = ((n - 1.0) / (n + 1.0)) * ((n - 1.0) / (n + 1.0));
  const double expected = le * (1.0 - r) / (1.0 + r);
  // 64 pixels x 16 rays x 64 frames: each ray carries Le or nothing, so its mean has a relative error of 0.2%.
  EXPECT_NEAR(layer_mean(*traced, view, settings, Layer::kLe, 64), expected, 0.01 * expected);
  // The filter Tf tints each refraction, not the reflections: the light refracts twice on its way through.
  Scene tinted = s;
  tinted.materials[0].tf = Vec3(0.5f);
  const auto traced_tinted = prepare_scene(tinted);
  const double tinted_expected = 0.25 * expected;
  EXPECT_NEAR(layer_mean(*traced_tinted, view, settings, Layer::kLe, 64), tinted_expected, 0.01 * tinted_expected);
}

}  // namespace
}  // namespace lueur
