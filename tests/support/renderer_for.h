#pragma once
// A scene renderer for a scene file's text, drawn with the source tree's shaders:
// for GL tests of what a scene builds (needs a current context, gl_test.h's).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "asset/scene_file.h"
#include "gl_test.h"
#include "render/scene_renderer.h"

namespace engine::test {

// Null, with the failure recorded, where the text does not parse or build.
inline std::unique_ptr<SceneRenderer> rendererFor(const std::string& text, const std::string& name) {
  auto scene = parseScene(text, name);
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  if (!scene) return nullptr;
  SceneRenderOptions options;
  options.shaderDir = shaderDir();
  auto renderer = SceneRenderer::create(*scene, options);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  return renderer.ok() ? std::move(renderer).value() : nullptr;
}

}  // namespace engine::test
