#pragma once
// The real scene renderer, offscreen (EGL), for the golden tests that hold it
// against the ray tracers.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "app/runner.h"
#include "core/image.h"
#include "../support/no_undeclared_uniforms.h"
#include "scene_game.h"

namespace engine::test {

// `scene` drawn at `width` x `height` with `options` (the shader folder is filled
// in); empty on failure.
inline Image rasterizedWith(const SceneDesc& scene, SceneRenderOptions options, int width, int height,
                            std::optional<double> time = std::nullopt) {
  options.shaderDir = std::string(ENGINE_SOURCE_DIR) + "/shaders";
  demo::SceneGame game(scene, options);
  RunOptions run;
  run.width = width;
  run.height = height;
  run.time = time;
  Image image;
  EXPECT_TRUE(runHeadless(Backend::Egl, game, run, &image).ok());
  return image;
}

}  // namespace engine::test
