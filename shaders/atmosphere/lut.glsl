// The sky tables' geometry and parameterisations (Hillaire 2020, after Bruneton and
// Neyret 2008), shared by the passes that build them (atmosphere/*.comp) and the
// programs that read them (sky.frag, the surfaces' aerial perspective). After
// common/atmosphere.glsl.
//
// A point is its altitude a above the ground and a direction the cosine mu of its
// angle from the local zenith. In metres the radii (6.36e6) swamp a camera's
// altitude (1.7): r^2 - R^2 and the like are written as products of the altitude
// (a (2R + a)), never as differences of squares, and each root is taken in the form
// that does not cancel.
#define ATMOSPHERE_PI 3.14159265358979

float atmosphereThickness(Atmosphere A) { return A.topRadius - A.bottomRadius; }

// r^2 - R^2 at altitude a.
float aboveGround2(Atmosphere A, float a) { return a * (2.0 * A.bottomRadius + a); }

// The distance from altitude a along mu to the top of the air (a below it).
float distanceToTop(Atmosphere A, float a, float mu) {
  float r = A.bottomRadius + a;
  float topMinusR2 = max(atmosphereThickness(A) - a, 0.0) * (A.topRadius + r);  // top^2 - r^2
  float root = sqrt(max(topMinusR2 + r * r * mu * mu, 0.0));
  return mu > 0.0 ? topMinusR2 / (r * mu + root) : root - r * mu;
}

// The distance from altitude a along mu to the ground, or -1 where the ray misses it.
float distanceToGround(Atmosphere A, float a, float mu) {
  if (mu >= 0.0) return -1.0;
  float r = A.bottomRadius + a;
  float h2 = aboveGround2(A, a);
  float disc = r * r * mu * mu - h2;
  if (disc < 0.0) return -1.0;
  return h2 / (sqrt(disc) - r * mu);
}

// A ray from altitude `altitude`: the cosines of its angle from the zenith (mu), of
// the sun's from the zenith (muSun) and of the angle between the ray and the sun (nu).
struct AtmosphereRay {
  float altitude;
  float mu;
  float muSun;
  float nu;
};

// The altitude and the sun's zenith cosine at distance t along the ray.
vec2 atmosphereRayAt(Atmosphere A, AtmosphereRay ray, float t) {
  float r = A.bottomRadius + ray.altitude;
  float h2 = aboveGround2(A, ray.altitude) + t * (t + 2.0 * r * ray.mu);  // r_t^2 - R^2
  float rt = sqrt(max(A.bottomRadius * A.bottomRadius + h2, 1.0));
  return vec2(h2 / (rt + A.bottomRadius), clamp((r * ray.muSun + t * ray.nu) / rt, -1.0, 1.0));
}

// Where a table's texel centres are: u in [0, 1] onto [0.5, size - 0.5] texels, and back.
float unitToTexelCentres(float u, float size) { return (0.5 + u * (size - 1.0)) / size; }
float texelCentresToUnit(float u, float size) { return (u * size - 0.5) / (size - 1.0); }

// The transmittance table (Bruneton's): x the distance to the top between its least
// and greatest at that altitude, y the altitude as rho = sqrt(r^2 - R^2) over the
// horizon's distance from the top.
#define TRANSMITTANCE_SIZE vec2(256.0, 64.0)
vec2 transmittanceUv(Atmosphere A, float a, float mu) {
  float H = sqrt(aboveGround2(A, atmosphereThickness(A)));
  float rho = sqrt(aboveGround2(A, a));
  float dMin = atmosphereThickness(A) - a, dMax = rho + H;
  float x = (distanceToTop(A, a, mu) - dMin) / (dMax - dMin);
  return vec2(unitToTexelCentres(clamp(x, 0.0, 1.0), TRANSMITTANCE_SIZE.x),
              unitToTexelCentres(clamp(rho / H, 0.0, 1.0), TRANSMITTANCE_SIZE.y));
}

// The altitude (x) and mu (y) of a transmittance texel.
vec2 transmittanceTexelRay(Atmosphere A, vec2 uv) {
  float H = sqrt(aboveGround2(A, atmosphereThickness(A)));
  float rho = H * texelCentresToUnit(uv.y, TRANSMITTANCE_SIZE.y);
  float a = rho * rho / (A.bottomRadius + sqrt(A.bottomRadius * A.bottomRadius + rho * rho));
  float dMin = atmosphereThickness(A) - a, dMax = rho + H;
  float d = dMin + texelCentresToUnit(uv.x, TRANSMITTANCE_SIZE.x) * (dMax - dMin);
  float r = A.bottomRadius + a;
  float topMinusR2 = (atmosphereThickness(A) - a) * (A.topRadius + r);
  float mu = d <= 0.0 ? 1.0 : (topMinusR2 - d * d) / (2.0 * r * d);
  return vec2(a, clamp(mu, -1.0, 1.0));
}

// The multiple-scattering table: x the sun's zenith cosine, y the altitude.
#define MULTI_SCATTERING_SIZE 32.0
vec2 multiScatteringUv(Atmosphere A, float a, float muSun) {
  return vec2(unitToTexelCentres(clamp(muSun * 0.5 + 0.5, 0.0, 1.0), MULTI_SCATTERING_SIZE),
              unitToTexelCentres(clamp(a / atmosphereThickness(A), 0.0, 1.0), MULTI_SCATTERING_SIZE));
}

// The sky-view table (192 x 108) about the camera's zenith: x the azimuth from the
// sun's (sqrt: finer toward the sun), y the zenith angle, the sky in the lower half
// and the ground in the upper, each squeezed toward the horizon (the paper's
// non-linear latitude), where the sky changes fastest.
#define SKY_VIEW_SIZE vec2(192.0, 108.0)
// The zenith angle of the horizon at altitude a is pi - beta: beta, from the
// horizon down to the nadir.
float horizonBeta(Atmosphere A, float a) {
  return acos(clamp(sqrt(aboveGround2(A, a)) / (A.bottomRadius + a), 0.0, 1.0));
}

vec2 skyViewUv(Atmosphere A, float a, float mu, float cosAzimuth) {
  float beta = horizonBeta(A, a);
  float zenithHorizon = ATMOSPHERE_PI - beta;
  float theta = acos(clamp(mu, -1.0, 1.0));
  float v = theta < zenithHorizon ? 0.5 * (1.0 - sqrt(max(1.0 - theta / zenithHorizon, 0.0)))
                                  : 0.5 + 0.5 * sqrt(clamp((theta - zenithHorizon) / beta, 0.0, 1.0));
  float u = sqrt(clamp(0.5 - 0.5 * cosAzimuth, 0.0, 1.0));
  return vec2(unitToTexelCentres(u, SKY_VIEW_SIZE.x), unitToTexelCentres(v, SKY_VIEW_SIZE.y));
}

// The zenith cosine (x) and the azimuth's cosine from the sun (y) of a sky-view texel.
vec2 skyViewTexelDirection(Atmosphere A, float a, vec2 uv) {
  float u = texelCentresToUnit(uv.x, SKY_VIEW_SIZE.x), v = texelCentresToUnit(uv.y, SKY_VIEW_SIZE.y);
  float beta = horizonBeta(A, a);
  float zenithHorizon = ATMOSPHERE_PI - beta;
  float theta;
  if (v < 0.5) {
    float c = 1.0 - 2.0 * v;
    theta = zenithHorizon * (1.0 - c * c);
  } else {
    float c = 2.0 * v - 1.0;
    theta = zenithHorizon + beta * c * c;
  }
  return vec2(cos(theta), 1.0 - 2.0 * u * u);
}

// The aerial-perspective volume: 32 x 32 froxels over the view, 32 slices to
// AERIAL_DEPTH metres spaced by the square of the slice (finer near the camera);
// in-scattered radiance in slices 0-31 of its 64, transmittance in 32-63.
#define AERIAL_SIZE 32.0
#define AERIAL_DEPTH 32000.0
float aerialSliceDistance(float slice) {
  float w = slice / AERIAL_SIZE;
  return AERIAL_DEPTH * w * w;
}
