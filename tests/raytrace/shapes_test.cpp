// Shapes on their own: the sphere's stable quadratic at small, large and grazing
// scales, the watertight triangle test on shared edges and vertices, and the ray
// origin offset that keeps a surface from hitting itself at 1e5 from the origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <type_traits>

#include "asset/texture_transform.h"
#include "raytrace/shapes.h"
#include "raytrace/texture.h"

namespace rt = engine::rt;

namespace {

template <typename T>
class ShapesTest : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(ShapesTest, Precisions);

template <typename T>
rt::Vec3<T> randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  glm::dvec3 v;
  do {
    v = glm::dvec3(n(rng), n(rng), n(rng));
  } while (glm::length(v) < 1e-6);
  return rt::Vec3<T>(glm::normalize(v));
}

// nextUp and nextDown step the bits inline; std::nextafter is what they must equal:
// 4 M random bit patterns (every sign, exponent and mantissa), and the neighbourhoods
// of the edges: both zeros, the denormals' ends, 1, the largest finite, the
// infinities.
TYPED_TEST(ShapesTest, NextUpAndDownAreNextafter) {
  using T = TypeParam;
  using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  constexpr T inf = std::numeric_limits<T>::infinity();
  std::int64_t checked = 0;
  auto check = [&](T v) {
    if (std::isnan(v)) return;
    ASSERT_EQ(std::bit_cast<Bits>(rt::nextUp(v)), std::bit_cast<Bits>(std::nextafter(v, inf))) << v;
    ASSERT_EQ(std::bit_cast<Bits>(rt::nextDown(v)), std::bit_cast<Bits>(std::nextafter(v, -inf))) << v;
    ++checked;
  };
  std::mt19937_64 rng(11);
  for (int i = 0; i < 4'000'000; ++i) check(std::bit_cast<T>(Bits(rng())));
  for (const T edge : {T(0), std::numeric_limits<T>::denorm_min(), std::numeric_limits<T>::min(), T(1),
                       std::numeric_limits<T>::max(), inf}) {
    for (const T signedEdge : {edge, -edge}) {
      T up = signedEdge, down = signedEdge;
      for (int i = 0; i < 1000; ++i, up = std::nextafter(up, inf), down = std::nextafter(down, -inf)) {
        check(up);
        check(down);
      }
    }
  }
  EXPECT_GT(checked, 4'000'000);
}

TYPED_TEST(ShapesTest, SphereHitsAtTheClosedFormDistance) {
  using T = TypeParam;
  const rt::Sphere<T> sphere{rt::Vec3<T>(0, 0, 5), T(1), 0};
  auto t = sphere.intersect(rt::Ray<T>{rt::Vec3<T>(0), rt::Vec3<T>(0, 0, 1)});
  ASSERT_TRUE(t);
  EXPECT_NEAR(double(*t), 4.0, 1e-6);
  // From inside, the far root.
  t = sphere.intersect(rt::Ray<T>{rt::Vec3<T>(0, 0, 5), rt::Vec3<T>(0, 0, 1)});
  ASSERT_TRUE(t);
  EXPECT_NEAR(double(*t), 1.0, 1e-6);
  // Behind the origin: no hit; tMax short of it: no hit.
  EXPECT_FALSE(sphere.intersect(rt::Ray<T>{rt::Vec3<T>(0), rt::Vec3<T>(0, 0, -1)}));
  EXPECT_FALSE(sphere.intersect(rt::Ray<T>{rt::Vec3<T>(0), rt::Vec3<T>(0, 0, 1), T(3.9)}));
}

// Rays passing the centre at distances just inside and just outside the radius:
// inside ones hit where the closed form says, outside ones miss, none gives NaN.
TYPED_TEST(ShapesTest, GrazingRaysHitInsideAndMissOutside) {
  using T = TypeParam;
  const double r = 1.0, dist = 10.0;
  const rt::Sphere<T> sphere{rt::Vec3<T>(0, 0, T(dist)), T(r), 0};
  const double rel = sizeof(T) == 4 ? 1e-4 : 1e-10;
  for (double f : {1.0 - 1e3 * rel, 1.0 - 10 * rel, 1.0 + 10 * rel, 1.0 + 1e3 * rel}) {
    for (int k = 0; k < 64; ++k) {
      const double phi = 2.0 * M_PI * k / 64.0;
      // A ray parallel to z at distance f r from the centre's axis.
      const glm::dvec3 o(f * r * std::cos(phi), f * r * std::sin(phi), 0.0);
      const auto t = sphere.intersect(rt::Ray<T>{rt::Vec3<T>(o), rt::Vec3<T>(0, 0, 1)});
      if (f < 1.0) {
        ASSERT_TRUE(t) << "f " << f << " phi " << phi;
        ASSERT_FALSE(std::isnan(double(*t)));
        const double expected = dist - std::sqrt(r * r - f * f * r * r);
        // The chord is short here, so t is sensitive: allow the float error of the
        // discriminant (about sqrt(eps) r) in float.
        EXPECT_NEAR(double(*t), expected, sizeof(T) == 4 ? 2e-3 : 1e-6);
      } else {
        EXPECT_FALSE(t) << "f " << f << " phi " << phi;
      }
    }
  }
}

TYPED_TEST(ShapesTest, TinyAndHugeSpheres) {
  using T = TypeParam;
  const double tol = sizeof(T) == 4 ? 1e-5 : 1e-12;
  // Radius 1e-3 at 3 m: t = 3 - 1e-3 to float's relative precision.
  const rt::Sphere<T> tiny{rt::Vec3<T>(0, 0, 3), T(1e-3), 0};
  auto t = tiny.intersect(rt::Ray<T>{rt::Vec3<T>(0), rt::Vec3<T>(0, 0, 1)});
  ASSERT_TRUE(t);
  EXPECT_NEAR(double(*t), 3.0 - 1e-3, 3.0 * tol);
  // Radius 1e5, a ray 1 m above its top pointing down: t = 1 within float's error at
  // the scale of the sphere (its centre and radius are 1e5).
  const rt::Sphere<T> huge{rt::Vec3<T>(0, T(-1e5), 0), T(1e5), 0};
  const rt::Ray<T> down{rt::Vec3<T>(0, 1, 0), rt::Vec3<T>(0, -1, 0)};
  t = huge.intersect(down);
  ASSERT_TRUE(t);
  EXPECT_NEAR(double(*t), 1.0, 4.0 * 1e5 * double(std::numeric_limits<T>::epsilon()));
  const auto si = huge.interaction(down, *t);
  EXPECT_NEAR(double(si.n.y), 1.0, 1e-6);
}

// Two triangles sharing an edge, neither axis aligned: rays aimed at points along the
// shared edge from many origins hit one of them, every time (Woop et al.'s property).
TYPED_TEST(ShapesTest, RaysAtASharedEdgeNeverSlipThrough) {
  using T = TypeParam;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int misses = 0, rays = 0;
  for (int quad = 0; quad < 20; ++quad) {
    const rt::Vec3<T> a = rt::Vec3<T>(T(u(rng) * 4 - 2), T(u(rng) * 4 - 2), T(u(rng) + 4));
    const rt::Vec3<T> b = a + rt::Vec3<T>(T(u(rng) * 2 + 0.5), T(u(rng) * 2 - 1), T(u(rng) - 0.5));
    // c and d on either side of the edge ab.
    const rt::Vec3<T> side = rt::Vec3<T>(T(u(rng) - 0.5), T(u(rng) + 0.5), T(u(rng) - 0.5));
    const rt::Vec3<T> c = (a + b) * T(0.5) + side;
    const rt::Vec3<T> d = (a + b) * T(0.5) - side;
    for (int i = 0; i < 500; ++i) {
      const T s = T(u(rng));
      const rt::Vec3<T> target = a + s * (b - a);
      const rt::Vec3<T> origin = rt::Vec3<T>(T(u(rng) * 2 - 1), T(u(rng) * 2 - 1), T(u(rng) * 2 - 1));
      const rt::Ray<T> ray{origin, target - origin};
      const bool hit = rt::intersectTriangle(ray, a, b, c) || rt::intersectTriangle(ray, b, a, d);
      misses += hit ? 0 : 1;
      ++rays;
    }
  }
  EXPECT_EQ(misses, 0) << "of " << rays << " rays";
}

// A fan of 12 triangles around one vertex: rays aimed at that vertex always hit.
TYPED_TEST(ShapesTest, RaysAtASharedVertexNeverSlipThrough) {
  using T = TypeParam;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const rt::Vec3<T> centre(T(0.3), T(-0.2), T(6.1));
  std::vector<rt::Vec3<T>> rim;
  for (int k = 0; k < 12; ++k) {
    const double phi = 2 * M_PI * k / 12;
    rim.push_back(centre + rt::Vec3<T>(T(std::cos(phi)), T(std::sin(phi)), T(0.3 * std::sin(3 * phi))));
  }
  int misses = 0;
  for (int i = 0; i < 2000; ++i) {
    const rt::Vec3<T> origin(T(u(rng)), T(u(rng)), T(u(rng)));
    const rt::Ray<T> ray{origin, centre - origin};
    bool hit = false;
    for (int k = 0; k < 12 && !hit; ++k) hit = bool(rt::intersectTriangle(ray, centre, rim[k], rim[(k + 1) % 12]));
    misses += hit ? 0 : 1;
  }
  EXPECT_EQ(misses, 0);
}

// Points on a sphere, a plane and a triangle 1e5 from the origin: rays leaving them
// into the outer hemisphere never hit the surface they leave (no self-shadowing).
TYPED_TEST(ShapesTest, OffsetRaysNeverHitTheirOwnSurfaceFarFromTheOrigin) {
  using T = TypeParam;
  std::mt19937 rng(3);
  const rt::Vec3<T> far(T(1e5), T(-1e5), T(1e5));
  const rt::Sphere<T> sphere{far + rt::Vec3<T>(0, 0, 0), T(1.5), 0};
  const rt::Vec3<T> pn = glm::normalize(rt::Vec3<T>(T(0.3), T(1), T(0.2)));
  const rt::Plane<T> plane{pn, glm::dot(pn, far), 0};
  const rt::Vec3<T> a = far + rt::Vec3<T>(-3, 0.1, -2), b = far + rt::Vec3<T>(4, -0.3, -1), c = far + rt::Vec3<T>(0, 0.2, 5);
  int selfHits = 0;
  for (int i = 0; i < 5000; ++i) {
    const rt::Vec3<T> toward = randomUnit<T>(rng);
    // A primary ray from outside to each surface, then a ray leaving the hit point.
    const rt::Vec3<T> eye = far + rt::Vec3<T>(20, 30, -25) + randomUnit<T>(rng);
    {
      const rt::Ray<T> ray{eye, sphere.center + toward * sphere.radius - eye};
      if (auto t = sphere.intersect(ray)) {
        const auto si = sphere.interaction(ray, *t);
        rt::Vec3<T> w = randomUnit<T>(rng);
        if (glm::dot(w, si.n) < 0) w = -w;
        selfHits += sphere.intersect(si.spawnRay(w)) ? 1 : 0;
      }
    }
    {
      const rt::Ray<T> ray{eye, far + toward * T(10) - eye};
      if (auto t = plane.intersect(ray)) {
        const auto si = plane.interaction(ray, *t);
        rt::Vec3<T> w = randomUnit<T>(rng);
        if (glm::dot(w, glm::dot(si.n, ray.d) < 0 ? si.n : -si.n) < 0) w = -w;
        selfHits += plane.intersect(si.spawnRay(w)) ? 1 : 0;
      }
    }
    {
      const rt::Ray<T> ray{eye, (a + b + c) / T(3) + toward - eye};
      if (auto hit = rt::intersectTriangle(ray, a, b, c)) {
        const auto si = rt::triangleInteraction(*hit, a, b, c);
        rt::Vec3<T> w = randomUnit<T>(rng);
        if (glm::dot(w, glm::dot(si.n, ray.d) < 0 ? si.n : -si.n) < 0) w = -w;
        selfHits += rt::intersectTriangle(si.spawnRay(w), a, b, c) ? 1 : 0;
      }
    }
  }
  EXPECT_EQ(selfHits, 0);
}

}  // namespace

// Texture sampling as GL does it for the rasterizer: bilinear between texel centres,
// sRGB decoded per texel before filtering, repeat outside [0, 1), and the row that
// v = 0 reads set by the origin.
TEST(RtTexture, BilinearSrgbRepeatAndOrigin) {
  engine::Image image(2, 1);
  const std::uint8_t white[4] = {255, 255, 255, 255}, black[4] = {0, 0, 0, 255};
  std::copy(white, white + 4, image.at(0, 0));
  std::copy(black, black + 4, image.at(1, 0));
  const rt::RtTexture t(image, rt::TextureOrigin::TopLeft);
  EXPECT_FLOAT_EQ(t.sample({0.25f, 0.5f}).x, 1.0f);   // texel 0's centre
  EXPECT_FLOAT_EQ(t.sample({0.75f, 0.5f}).x, 0.0f);   // texel 1's centre
  EXPECT_FLOAT_EQ(t.sample({0.5f, 0.5f}).x, 0.5f);    // linear average, not sRGB 128
  EXPECT_FLOAT_EQ(t.sample({0.0f, 0.5f}).x, 0.5f);    // wraps to texel 1 on the left
  EXPECT_FLOAT_EQ(t.sample({1.25f, 0.5f}).x, 1.0f);   // repeat
  EXPECT_FLOAT_EQ(t.sample({-0.75f, 0.5f}).x, 1.0f);

  engine::Image gray(1, 1);
  const std::uint8_t g[4] = {188, 188, 188, 255};
  std::copy(g, g + 4, gray.at(0, 0));
  // sRGB 188 / 255 is linear ((0.737 + 0.055) / 1.055)^2.4 = 0.5029.
  EXPECT_NEAR(rt::RtTexture(gray, rt::TextureOrigin::TopLeft).sample({0.3f, 0.7f}).y, 0.5029f, 1e-4f);

  engine::Image column(1, 2);
  std::copy(white, white + 4, column.at(0, 0));
  std::copy(black, black + 4, column.at(0, 1));
  EXPECT_FLOAT_EQ(rt::RtTexture(column, rt::TextureOrigin::TopLeft).sample({0.5f, 0.25f}).z, 1.0f);
  EXPECT_FLOAT_EQ(rt::RtTexture(column, rt::TextureOrigin::BottomLeft).sample({0.5f, 0.25f}).z, 0.0f);
}

// Mipmaps as glGenerateMipmap makes them, sampled as GL_LINEAR_MIPMAP_LINEAR does: a
// 4 x 4 black-and-white checkerboard of single texels averages to linear grey from
// the first level down; a footprint of a texel or less reads the full resolution,
// two texels the first level, in between a blend of the two.
TEST(RtTexture, MipmapsAverageAndTheFootprintPicksTheLevel) {
  engine::Image checker(4, 4);
  const std::uint8_t white[4] = {255, 255, 255, 255}, black[4] = {0, 0, 0, 255};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) std::copy((x + y) % 2 ? black : white, ((x + y) % 2 ? black : white) + 4, checker.at(x, y));
  const rt::RtTexture t(checker, rt::TextureOrigin::TopLeft);
  EXPECT_EQ(t.levels(), 3);                                   // 4x4, 2x2, 1x1
  const glm::vec2 centre0(0.125f, 0.125f);                    // texel (0, 0), white
  EXPECT_FLOAT_EQ(t.sample(centre0).x, 1.0f);
  EXPECT_FLOAT_EQ(t.sample(centre0, 0.25f).x, 1.0f);          // one texel: level 0
  EXPECT_FLOAT_EQ(t.sample(centre0, 0.5f).x, 0.5f);           // two texels: level 1
  EXPECT_FLOAT_EQ(t.sample(centre0, 100.0f).x, 0.5f);         // clamped to the last level
  // sqrt(2) texels: level 0.5, half way between white and grey.
  EXPECT_NEAR(t.sample(centre0, 0.25f * std::sqrt(2.0f)).x, 0.75f, 1e-5f);
  // Odd and non-square sizes halve to floor(size / 2), down to 1 x 1.
  EXPECT_EQ(rt::RtTexture(engine::Image(5, 2), rt::TextureOrigin::TopLeft).levels(), 3);  // 5x2, 2x1, 1x1
  EXPECT_EQ(rt::RtTexture(engine::Image(1, 1), rt::TextureOrigin::TopLeft).levels(), 1);
}

namespace {

// A linear texture of `w` x `h` texels whose red is each texel's index / (w h - 1).
rt::RtTexture rampTexture(int w, int h) {
  engine::Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto r = std::uint8_t(std::lround(255.0 * (y * w + x) / (w * h - 1)));
      const std::uint8_t p[4] = {r, 0, 0, 255};
      std::copy(p, p + 4, image.at(x, y));
    }
  return rt::RtTexture(image, rt::TextureOrigin::TopLeft, rt::TextureEncoding::Linear);
}

}  // namespace

// glTF's wrap modes as GL applies them to texel indices (OpenGL 4.5, 8.14.2), on a
// 4-texel ramp 0, 1/3, 2/3, 1 at texel centres and edges past [0, 1].
TEST(RtTexture, WrapModesMatchGl) {
  using engine::TextureWrap;
  rt::RtTexture t = rampTexture(4, 1);
  auto at = [&](float u) { return t.sample(glm::vec2(u, 0.5f)).x; };
  t.setWrap(TextureWrap::Repeat, TextureWrap::Repeat);
  EXPECT_FLOAT_EQ(at(1.125f), 0.0f);
  EXPECT_FLOAT_EQ(at(-0.125f), 1.0f);
  EXPECT_FLOAT_EQ(at(1.0f), 0.5f);  // between texel 3 and texel 0
  t.setWrap(TextureWrap::ClampToEdge, TextureWrap::Repeat);
  EXPECT_FLOAT_EQ(at(1.125f), 1.0f);
  EXPECT_FLOAT_EQ(at(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(at(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(at(-7.5f), 0.0f);
  EXPECT_FLOAT_EQ(at(0.25f), 1.0f / 6.0f);  // inside, bilinear as before
  t.setWrap(TextureWrap::MirroredRepeat, TextureWrap::Repeat);
  EXPECT_FLOAT_EQ(at(1.125f), 1.0f);        // mirrored: texel 3 again
  EXPECT_FLOAT_EQ(at(1.375f), 2.0f / 3.0f);  // texel 2
  EXPECT_FLOAT_EQ(at(1.0f), 1.0f);          // texels 3 and its mirror
  EXPECT_FLOAT_EQ(at(-0.125f), 0.0f);
  EXPECT_FLOAT_EQ(at(2.125f), 0.0f);        // a period is 2
  EXPECT_FLOAT_EQ(at(-1.875f), 0.0f);
  // t wraps by its own mode.
  rt::RtTexture column = rampTexture(1, 4);
  column.setWrap(TextureWrap::Repeat, TextureWrap::ClampToEdge);
  EXPECT_FLOAT_EQ(column.sample(glm::vec2(0.5f, 1.125f)).x, 1.0f);
  column.setWrap(TextureWrap::ClampToEdge, TextureWrap::Repeat);
  EXPECT_FLOAT_EQ(column.sample(glm::vec2(0.5f, 1.125f)).x, 0.0f);
}

namespace {

// GL's wrap by its modular formula (OpenGL 4.5, 8.14.2), the tracer's before it
// skipped the division: the oracle for the sweep below.
int glWrap(int i, int n, engine::TextureWrap mode) {
  const auto mod = [](int a, int m) { return ((a % m) + m) % m; };
  switch (mode) {
    case engine::TextureWrap::ClampToEdge: return std::clamp(i, 0, n - 1);
    case engine::TextureWrap::MirroredRepeat: {
      const int a = mod(i, 2 * n) - n;
      return (n - 1) - (a >= 0 ? a : -(1 + a));
    }
    case engine::TextureWrap::Repeat: break;
  }
  return mod(i, n);
}

// One level's bilinear tap, written as texture.cpp wrote it before: each coordinate
// reduced to its wrap's period, then each of the four texel indices wrapped on its own.
glm::vec4 oracleBilinear(const rt::RtTexture& t, int level, glm::vec2 uv) {
  using engine::TextureWrap;
  const auto reduce = [](float x, TextureWrap mode) {
    if (mode == TextureWrap::ClampToEdge) return std::clamp(x, 0.0f, 1.0f);
    if (mode == TextureWrap::MirroredRepeat) return x - 2.0f * std::floor(0.5f * x);
    return x - std::floor(x);
  };
  const glm::ivec2 size = t.levelSize(level);
  const std::vector<glm::vec4>& texels = t.levelTexels(level);
  const float u = reduce(uv.x, t.wrapS()) * float(size.x) - 0.5f;
  const float v = reduce(uv.y, t.wrapT()) * float(size.y) - 0.5f;
  if (!std::isfinite(u) || !std::isfinite(v)) return texels[0];
  const float fu = std::floor(u), fv = std::floor(v);
  const float tu = u - fu, tv = v - fv;
  const int x0 = glWrap(int(fu), size.x, t.wrapS()), x1 = glWrap(int(fu) + 1, size.x, t.wrapS());
  const int y0 = glWrap(int(fv), size.y, t.wrapT()), y1 = glWrap(int(fv) + 1, size.y, t.wrapT());
  const auto at = [&](int x, int y) { return texels[std::size_t(y) * std::size_t(size.x) + std::size_t(x)]; };
  return glm::mix(glm::mix(at(x0, y0), at(x1, y0), tu), glm::mix(at(x0, y1), at(x1, y1), tu), tv);
}

bool sameBits(glm::vec4 a, glm::vec4 b) {
  for (int i = 0; i < 4; ++i)
    if (std::bit_cast<std::uint32_t>(a[i]) != std::bit_cast<std::uint32_t>(b[i])) return false;
  return true;
}

}  // namespace

// The bilinear tap's wrap without a division (each coordinate reduced once, a texel
// pair wrapped by a check at each edge) gives the very bits of the modular formula:
// every pair of wrap modes on 1x1, 2x1, 3x5, 7x4 and 256x256 texels, 2.25 M uv:
// uniform over many periods, within a few ulps of every texel edge and period edge
// (0, 1, 2, -1, where reduce() rounds to the period's end), far from zero (10^5
// periods out) and tiny negatives that reduce to exactly 1; and 100 k trilinear
// taps, whose two levels share the once-reduced coordinates.
TEST(RtTexture, WrapWithoutDivisionMatchesTheModularFormulaBitForBit) {
  using engine::TextureWrap;
  const TextureWrap modes[] = {TextureWrap::Repeat, TextureWrap::ClampToEdge, TextureWrap::MirroredRepeat};
  const glm::ivec2 sizes[] = {{1, 1}, {2, 1}, {3, 5}, {7, 4}, {256, 256}};
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> wide(-8.0f, 8.0f), unit(0.0f, 1.0f);
  std::uniform_int_distribution<int> ulps(-4, 4), kind(0, 3);
  const auto coordinate = [&](int n) {
    switch (kind(rng)) {
      case 0: return wide(rng);
      case 1: {  // near a texel edge or centre, or a period's end, a few ulps either side
        const float edge = float(std::uniform_int_distribution<int>(-2 * n, 4 * n)(rng)) / float(2 * n);
        float x = edge;
        for (int k = ulps(rng); k != 0; k += k > 0 ? -1 : 1) x = std::nextafter(x, k > 0 ? 1e30f : -1e30f);
        return x;
      }
      case 2: return 1e5f + unit(rng) * 64.0f - 32.0f;  // far out: the fraction's precision
      default: return -std::ldexp(unit(rng), -std::uniform_int_distribution<int>(20, 140)(rng));  // reduces to 1
    }
  };
  int cases = 0;
  for (const glm::ivec2 size : sizes) {
    engine::Image image(size.x, size.y);
    for (auto& byte : image.pixels) byte = std::uint8_t(rng());
    for (const TextureWrap s : modes)
      for (const TextureWrap t : modes) {
        rt::RtTexture texture(image, rt::TextureOrigin::TopLeft);
        texture.setWrap(s, t);
        for (int i = 0; i < 50000; ++i, ++cases) {
          const glm::vec2 uv(coordinate(size.x), coordinate(size.y));
          const glm::vec4 got = texture.sampleRgba(uv);
          const glm::vec4 want = oracleBilinear(texture, 0, uv);
          ASSERT_TRUE(sameBits(got, want)) << size.x << "x" << size.y << " wrap " << int(s) << "/" << int(t)
                                           << " uv (" << uv.x << ", " << uv.y << ")";
        }
      }
  }
  EXPECT_EQ(cases, 5 * 9 * 50000);
  // Trilinear: the coordinates reduced once serve both levels. A footprint of 1 to 2
  // of level 0's texels puts GL's level of detail, log2 of it, between levels 0 and 1.
  rt::RtTexture texture = rampTexture(7, 4);
  texture.setWrap(TextureWrap::MirroredRepeat, TextureWrap::Repeat);
  for (int i = 0; i < 100000; ++i) {
    const glm::vec2 uv(coordinate(7), coordinate(4));
    const float footprint = (1.0f + unit(rng)) / 7.0f;
    const float lod = std::log2(footprint * 7.0f);
    const glm::vec4 want = glm::mix(oracleBilinear(texture, 0, uv), oracleBilinear(texture, 1, uv), lod);
    ASSERT_TRUE(sameBits(texture.sampleRgba(uv, footprint), want)) << "uv (" << uv.x << ", " << uv.y << ")";
  }
}

// A slot's uv set and KHR_texture_transform: the texture reads set 1 through the
// matrix, the same matrix the rasterizer takes as a uniform.
TEST(RtTexture, SamplesItsUvSetThroughTheTransform) {
  using engine::TextureWrap;
  rt::RtTexture t = rampTexture(4, 1);
  t.setMapping(1, engine::textureTransformMatrix({0.5f, 0.0f}, 0.0f, {1.0f, 1.0f}));
  // Set 1 at texel 0's centre, offset by half the width: texel 2. Set 0 is ignored.
  EXPECT_FLOAT_EQ(t.sample(rt::HitUv({0.875f, 0.5f}, {0.125f, 0.5f})).x, 2.0f / 3.0f);
  // A scale of 2 doubles the footprint: one texel at scale 1 (level 0) is two (level 1).
  t.setMapping(0, engine::textureTransformMatrix({0.0f, 0.0f}, 0.0f, {2.0f, 2.0f}));
  // At u 0.125 (after the scale) level 0 reads texel 0 (0); level 1 (texels 1/6, 5/6)
  // reads 3/4 of the way from 5/6 (wrapped) to 1/6: 1/3.
  EXPECT_NEAR(t.sample(glm::vec2(0.0625f, 0.5f), 0.25f).x, 1.0f / 3.0f, 1e-5f);

  // A quarter turn on a 2 x 2 ramp: (u, v) -> (v, -u), so set 0's (0.25, 0.75) reads
  // (0.75, -0.25): texel (1, 1) when t repeats, (1, 0) when it clamps.
  rt::RtTexture square = rampTexture(2, 2);
  square.setMapping(0, engine::textureTransformMatrix({0, 0}, float(std::numbers::pi / 2), {1, 1}));
  EXPECT_NEAR(square.sample(glm::vec2(0.25f, 0.75f)).x, 1.0f, 1e-5f);
  square.setWrap(TextureWrap::Repeat, TextureWrap::ClampToEdge);
  EXPECT_NEAR(square.sample(glm::vec2(0.25f, 0.75f)).x, 1.0f / 3.0f, 1e-5f);
}
