#pragma once
// The Whitted tracer's image of a scene at pixel centres (one ray a pixel, as the
// rasterizer samples), for the tests that hold the rasterizer against it.
#include <gtest/gtest.h>

#include "asset/scene_desc.h"
#include "core/image.h"
#include "raytrace/scene_builder.h"

namespace engine::test {

inline rt::RenderSettings pixelCentres(int width, int height) {
  rt::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.samplesPerPixel = 1;
  return settings;
}

// Empty, with the test failed, where the tracer fails.
inline Image tracedAtPixelCentres(const SceneDesc& scene, int width, int height, double time = 0.0) {
  auto traced = rt::raytraceScene(scene, time, pixelCentres(width, height));
  EXPECT_TRUE(traced.ok()) << traced.error().message;
  return traced.ok() ? traced->image : Image{};
}

}  // namespace engine::test
