// The physically based sky's tables (render/atmosphere_tables.h) on the GL: the
// transmittance table against the C++ quadrature of the shared text's extinction
// along the same rays, the rebuilds (only when the sun or the camera's place moves),
// and what --describe says of them.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../support/gl_test.h"
#include "../support/renderer_for.h"
#include "../support/quadrature.h"
#include "asset/scene_file.h"
#include "render/atmosphere_tables.h"
#include "render/camera.h"
#include "render/ibl.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

using namespace engine;
using engine::test::GlTest;

namespace {

constexpr const char* kSkyScene = R"({
  "camera": {"position": [0, 1.7, 0], "direction": [0, 0, -1], "fovy": 70, "far": 20000},
  "lights": [{"type": "sun", "direction": [0.4, 0.17, -0.9], "intensity": 10, "angle": 0.53}],
  "primitives": [{"type": "sphere", "center": [0, 1, -10], "radius": 1, "material": "m"}],
  "materials": {"m": {"color": [0.5, 0.5, 0.5], "roughness": 0.5}},
  "atmosphere": {},
  "render": {"ibl_size": 16}
})";

std::unique_ptr<SceneRenderer> rendererFor(const std::string& text) { return test::rendererFor(text, "sky.json"); }

// The transmittance along (altitude, mu) to the top of the air by adaptive Simpson
// over the ray in double: the reference the table and atmosphereTransmittance share.
glm::dvec3 referenceTransmittance(const atmospheretext::Atmosphere& air, double altitude, double mu) {
  const double bottom = air.bottomRadius, r = bottom + altitude, top = air.topRadius;
  const double length = -r * mu + std::sqrt(top * top - r * r * (1.0 - mu * mu));
  glm::dvec3 depth;
  for (int c = 0; c < 3; ++c) {
    // In double throughout: the text's float altitude would make the integrand a
    // staircase that Simpson halves without end.
    const double scattering[3] = {air.rayleighScattering[c], air.mieScattering[c] + air.mieAbsorption[c],
                                  air.ozoneAbsorption[c]};
    const auto extinction = [&](double t) {
      const double at = std::sqrt(r * r + t * t + 2.0 * r * t * mu) - bottom;
      return scattering[0] * std::exp(-at / air.rayleighScaleHeight) + scattering[1] * std::exp(-at / air.mieScaleHeight) +
             scattering[2] * std::max(0.0, 1.0 - std::abs(at - air.ozoneCenter) / air.ozoneHalfWidth);
    };
    // The ozone's tent has corners: integrated in pieces split at them where the
    // ray crosses their altitudes would be exact; Simpson's halving finds them well
    // enough at 1e-12 of a depth that is at least 1e-5.
    depth[c] = test::integrate(extinction, 0.0, length, 1e-12, 24);
  }
  return glm::exp(-depth);
}

}  // namespace

class SkyTables : public GlTest {};
ENGINE_INSTANTIATE_OFFSCREEN_EGL(SkyTables);

// Texels of the table's rows 0 (the ground) and 32 against the quadrature at the
// texel's own ray, Bruneton's parameterisation worked out here in double: x the
// distance to the top between its least (straight up) and greatest (the horizon),
// y rho = sqrt(r^2 - R^2) over the top's horizon distance H.
TEST_P(SkyTables, TransmittanceTableMatchesTheQuadrature) {
  const AtmosphereDesc desc;
  auto tables = AtmosphereTables::create(test::shaderDir(), desc);
  ASSERT_TRUE(tables.ok()) << tables.error().message;
  const auto& air = (*tables)->air();
  std::vector<glm::vec4> texels(256 * 64);
  glGetTextureImage((*tables)->transmittanceTable().id(), 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(glm::vec4)),
                    texels.data());
  const double R = desc.planetRadius, top = R + desc.thickness, H = std::sqrt(top * top - R * R);
  double worst = 0.0;
  for (int row : {0, 32, 63}) {
    const double rho = H * row / 63.0, r = std::sqrt(rho * rho + R * R);
    for (int column : {0, 64, 128, 192, 240, 255}) {
      const double dMin = top - r, dMax = rho + H;
      const double d = dMin + column / 255.0 * (dMax - dMin);
      const double mu = d <= 0.0 ? 1.0 : std::clamp((top * top - r * r - d * d) / (2.0 * r * d), -1.0, 1.0);
      const glm::dvec3 expected = referenceTransmittance(air, r - R, mu);
      const glm::vec3 cpu = atmosphereTransmittance(air, r - R, mu);
      const glm::vec4 gpu = texels[size_t(row * 256 + column)];
      for (int c = 0; c < 3; ++c) {
        // In optical depth: the horizon's blue is exp(-30), where a relative error
        // of the transmittance means nothing.
        const double depth = -std::log(expected[c]);
        const double gpuError = std::abs(-std::log(double(gpu[c])) - depth) / std::max(depth, 1e-3);
        worst = std::max(worst, gpuError);
        // Both midpoint rules space their steps by the square, short at the ray's
        // start, where a ray from the ground meets its densest air. A ray from the top
        // of the air that grazes down and out again (row 63) is densest in its middle:
        // there the C++ rule's 512 steps measured 5.6e-4 of a depth of 2e-5 and the
        // table's 64 float steps 4.7e-4, transmittances off by 1e-8. 1e-3 holds both
        // with twice the margin; a wrong parameterisation or layer is off by tens of
        // percent.
        EXPECT_NEAR(-std::log(double(cpu[c])), depth, 1e-3 * depth) << "row " << row << " column " << column;
        EXPECT_LT(gpuError, 1e-3) << "row " << row << " column " << column << " channel " << c << ": "
                                  << gpu[c] << " against " << expected[c];
      }
    }
  }
  std::printf("transmittance table: worst optical depth error %.2e\n", worst);
}

// The sky-view table follows the sun and the camera's place, and nothing else: the
// same frame again builds nothing, a camera a few metres away neither; a sun turned
// builds once.
TEST_P(SkyTables, SkyViewIsRebuiltOnlyWhenTheSunOrThePlaceMoves) {
  auto tables = AtmosphereTables::create(test::shaderDir(), AtmosphereDesc{});
  ASSERT_TRUE(tables.ok()) << tables.error().message;
  AtmosphereTables& t = **tables;
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.5f, -0.8f)), illuminance(3.14f);
  EXPECT_TRUE(t.update(sun, illuminance, glm::dvec3(0.0, 1.7, 0.0)));
  EXPECT_FALSE(t.update(sun, illuminance, glm::dvec3(0.0, 1.7, 0.0)));
  EXPECT_FALSE(t.update(sun, illuminance, glm::dvec3(3.0, 2.2, -4.0)));
  EXPECT_EQ(t.skyBuilds(), 1);
  EXPECT_TRUE(t.update(glm::normalize(glm::vec3(0.3f, 0.6f, -0.8f)), illuminance, glm::dvec3(0.0, 1.7, 0.0)));
  EXPECT_TRUE(t.update(glm::normalize(glm::vec3(0.3f, 0.6f, -0.8f)), illuminance, glm::dvec3(0.0, 500.0, 0.0)));
  EXPECT_EQ(t.skyBuilds(), 3);
}

// Through the renderer: frames of a still scene build the sky once (at load) and the
// aerial perspective once; the time of day's knob rebuilds both at the next frame,
// the ambient's environment with them (brighter at 60 degrees than at 10, bluer
// overhead than at 2), and the sun's colour that shades follows the air (redder at
// 2 degrees than at 60).
TEST_P(SkyTables, TheTimeOfDayRebuildsTheSky) {
  auto renderer = rendererFor(kSkyScene);
  ASSERT_NE(renderer, nullptr);
  auto target = RenderTarget::create(64, 64, 1);
  ASSERT_TRUE(target.ok());
  target->bind();
  const Camera camera = renderer->initialCamera();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(renderer->render(camera, 64, 64).ok());
  const AtmosphereTables* tables = renderer->atmosphereTables();
  ASSERT_NE(tables, nullptr);
  EXPECT_EQ(tables->skyBuilds(), 1);
  EXPECT_EQ(tables->aerialBuilds(), 1);  // the same view three times
  const auto skyAbove = [&] { return renderer->environmentLighting()->sh().irradiance(glm::vec3(0.0f, 1.0f, 0.0f)); };
  const glm::vec3 morning = skyAbove();
  renderer->setSunElevation(60.0);
  EXPECT_NEAR(renderer->sunElevationDegrees(), 60.0, 1e-5);  // kept as float
  ASSERT_TRUE(renderer->render(camera, 64, 64).ok());
  EXPECT_EQ(tables->skyBuilds(), 2);
  EXPECT_EQ(tables->aerialBuilds(), 2);
  const glm::vec3 high = tables->sunTransmittance(), midday = skyAbove();
  renderer->setSunElevation(2.0);
  ASSERT_TRUE(renderer->render(camera, 64, 64).ok());
  const glm::vec3 low = tables->sunTransmittance(), sunset = skyAbove();
  EXPECT_GT(midday.g, 1.5f * morning.g);
  EXPECT_GT(midday.b / midday.r, sunset.b / sunset.r);
  // exp(-(tau_blue - tau_red) / sin(elevation)) with the default layers' zenith
  // depths: 0.78 at 60 degrees, 0.02 at 2 (through 20 air masses).
  EXPECT_GT(high.b / high.r, 0.7f);
  EXPECT_LT(low.b / low.r, 0.05f);
}

// --describe lists the tables with their sizes where the scene has an atmosphere,
// and no table where it has none.
TEST_P(SkyTables, DescribeListsTheTables) {
  auto sky = rendererFor(kSkyScene);
  ASSERT_NE(sky, nullptr);
  EXPECT_NE(sky->describe().find("atmosphere(transmittance 256x64, multi-scattering 32x32, sky-view 192x108, "
                                 "aerial-perspective 32x32x32)"),
            std::string::npos)
      << sky->describe();
  auto plain = rendererFor(R"({"lights": [{"type": "sun", "direction": [0, 1, 0]}],
                               "sky": {"zenith": [0.1, 0.3, 1.0]}})");
  ASSERT_NE(plain, nullptr);
  EXPECT_EQ(plain->describe().find("atmosphere"), std::string::npos) << plain->describe();
}
