// A planet's atmosphere, written once (Hillaire 2020, "A Scalable and Production
// Ready Sky and Atmosphere Rendering Technique"; Bruneton and Neyret 2008's layers):
// the air's three layers and what they scatter and absorb at an altitude. The CPU
// path tracer renders it as a medium with this text (core/atmosphere.h), the
// rasterizer builds its sky tables with it; tests/core/shading_texts_test.cpp
// compares the two compiles.
//
// Metres and per-metre coefficients; the altitude is above the planet's surface (the
// scene's y = 0). In the subset of GLSL and C++ that common/brdf.glsl keeps to.
#ifndef BRDF_INLINE
#define BRDF_INLINE
#endif

// asset/scene_desc.h's AtmosphereDesc, as the shaders take it.
struct Atmosphere {
  float bottomRadius;  // the planet's
  float topRadius;     // the air's top
  vec3 rayleighScattering;
  float rayleighScaleHeight;
  vec3 mieScattering;
  vec3 mieAbsorption;
  float mieScaleHeight;
  float mieAnisotropy;
  vec3 ozoneAbsorption;
  float ozoneCenter;
  float ozoneHalfWidth;
  vec3 groundAlbedo;
};

// The layers' densities at `altitude`, relative to their coefficients: x Rayleigh's
// and y Mie's fall exponentially by their scale heights, z ozone's is a tent peaking
// at ozoneCenter. Below the ground they go on as above it (a scene's valley).
BRDF_INLINE vec3 atmosphereDensities(Atmosphere a, float altitude) {
  return vec3(exp(-altitude / a.rayleighScaleHeight), exp(-altitude / a.mieScaleHeight),
              max(0.0f, 1.0f - abs(altitude - a.ozoneCenter) / a.ozoneHalfWidth));
}

// Extinction per metre at those densities: Rayleigh's scattering, Mie's scattering
// and absorption, ozone's absorption.
BRDF_INLINE vec3 atmosphereExtinction(Atmosphere a, vec3 densities) {
  return a.rayleighScattering * densities.x + (a.mieScattering + a.mieAbsorption) * densities.y +
         a.ozoneAbsorption * densities.z;
}

// The greatest density of each layer between two altitudes (lo <= hi): the
// exponentials' at the lower one, the tent's at its peak where that lies between.
// A majorant for tracking a ray through the air.
BRDF_INLINE vec3 atmosphereDensityBound(Atmosphere a, float lo, float hi) {
  float peak = min(max(a.ozoneCenter, lo), hi);
  return vec3(exp(-lo / a.rayleighScaleHeight), exp(-lo / a.mieScaleHeight),
              max(0.0f, 1.0f - abs(peak - a.ozoneCenter) / a.ozoneHalfWidth));
}

// The least density of each layer between two altitudes (lo <= hi): the
// exponentials' at the higher one, the tent's at whichever end is further from its
// peak.
BRDF_INLINE vec3 atmosphereDensityFloor(Atmosphere a, float lo, float hi) {
  float far = abs(lo - a.ozoneCenter) > abs(hi - a.ozoneCenter) ? lo : hi;
  return vec3(exp(-hi / a.rayleighScaleHeight), exp(-hi / a.mieScaleHeight),
              max(0.0f, 1.0f - abs(far - a.ozoneCenter) / a.ozoneHalfWidth));
}

// The sun's disk darkened toward its limb, for the fraction `r` of the disk's radius
// from its centre (0..1): mu^alpha with mu the cosine at the sun's surface and alpha
// per channel for 680, 550 and 440 nm (the power law Hillaire's sky takes).
BRDF_INLINE vec3 sunLimbDarkening(float r) {
  float mu = sqrt(max(0.0f, 1.0f - r * r));
  return pow(vec3(mu), vec3(0.397f, 0.503f, 0.652f));
}
