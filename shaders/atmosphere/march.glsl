// Light scattered toward a ray's origin along the ray (Hillaire 2020, section 4),
// per unit of the sun's illuminance: the sun's light scattered once at each step,
// with what reaches that step from the sun (the transmittance table, nothing where
// the planet is in the way), plus every higher order from the multiple-scattering
// table. For the compute passes that build the tables; after common/atmosphere.glsl,
// common/phase.glsl (and common/brdf.glsl before it) and atmosphere/lut.glsl.
//
// MULTI_SCATTERING_PASS: the multiple-scattering table's own march, scattering
// isotropically and without higher orders (its second order and f_ms, the paper's
// eq. 6-7).
uniform Atmosphere u_atmosphere;
layout(binding = UNIT_SKY_TRANSMITTANCE) uniform sampler2D u_transmittance;
#ifndef MULTI_SCATTERING_PASS
layout(binding = UNIT_SKY_MULTI_SCATTERING) uniform sampler2D u_multiScattering;
#endif

// The transmittance from altitude a toward a sun at zenith cosine muSun.
vec3 sunTransmittance(float a, float muSun) {
  if (distanceToGround(u_atmosphere, a, muSun) >= 0.0) return vec3(0.0);
  return texture(u_transmittance, transmittanceUv(u_atmosphere, a, muSun)).rgb;
}

struct Scattering {
  vec3 radiance;       // in-scattered, per unit sun illuminance
  vec3 transmittance;  // from the ray's origin
  vec3 multiScatteringAs1;  // f_ms's integrand summed (MULTI_SCATTERING_PASS)
};

Scattering noScattering() { return Scattering(vec3(0.0), vec3(1.0), vec3(0.0)); }

// One step of length dt about the distance t: the step's source taken constant and
// integrated against its own transmittance, (S - S T) / sigma_t (the paper's
// energy-conserving step).
void scatterStep(AtmosphereRay ray, float t, float dt, inout Scattering s) {
  vec2 at = atmosphereRayAt(u_atmosphere, ray, t);
  vec3 densities = atmosphereDensities(u_atmosphere, at.x);
  vec3 rayleigh = u_atmosphere.rayleighScattering * densities.x;
  vec3 mie = u_atmosphere.mieScattering * densities.y;
  vec3 extinction = max(atmosphereExtinction(u_atmosphere, densities), vec3(1e-20));
  vec3 toSun = sunTransmittance(at.x, at.y);
#ifdef MULTI_SCATTERING_PASS
  vec3 source = (rayleigh + mie) * toSun / (4.0 * ATMOSPHERE_PI);
#else
  vec3 multiple = texture(u_multiScattering, multiScatteringUv(u_atmosphere, at.x, at.y)).rgb;
  vec3 source = (rayleigh * phaseRayleigh(ray.nu) + mie * phaseHenyeyGreenstein(ray.nu, u_atmosphere.mieAnisotropy)) *
                    toSun + (rayleigh + mie) * multiple;
#endif
  vec3 stepTransmittance = exp(-extinction * dt);
  vec3 absorbed = (1.0 - stepTransmittance) / extinction;
  s.radiance += s.transmittance * source * absorbed;
  s.multiScatteringAs1 += s.transmittance * (rayleigh + mie) * absorbed;
  s.transmittance *= stepTransmittance;
}

// `steps` steps from t0 to t1, spaced linearly, or with `quadratic` by the square
// (short near t0, where a ray from the ground meets its densest air).
void scatterAlong(AtmosphereRay ray, float t0, float t1, int steps, bool quadratic, inout Scattering s) {
  float previous = t0;
  for (int i = 0; i < steps; ++i) {
    float x = float(i + 1) / float(steps), xMid = (float(i) + 0.5) / float(steps);
    float next = t0 + (t1 - t0) * (quadratic ? x * x : x);
    float mid = t0 + (t1 - t0) * (quadratic ? xMid * xMid : xMid);
    scatterStep(ray, mid, next - previous, s);
    previous = next;
  }
}

// Where the ray ends: the ground (x: its distance, y: 1) or the top of the air (y: 0).
vec2 atmosphereRayEnd(AtmosphereRay ray) {
  float ground = distanceToGround(u_atmosphere, ray.altitude, ray.mu);
  return ground >= 0.0 ? vec2(ground, 1.0) : vec2(distanceToTop(u_atmosphere, ray.altitude, ray.mu), 0.0);
}

// The Lambertian ground at the end of a ray, lit by the sun through the air and by
// `skyIrradiance` (both per unit sun illuminance), as seen through the ray's air.
vec3 groundRadiance(AtmosphereRay ray, float t, vec3 skyIrradiance, Scattering s) {
  float muSun = atmosphereRayAt(u_atmosphere, ray, t).y;
  vec3 irradiance = sunTransmittance(0.0, muSun) * max(muSun, 0.0) + skyIrradiance;
  return s.transmittance * u_atmosphere.groundAlbedo / ATMOSPHERE_PI * irradiance;
}
