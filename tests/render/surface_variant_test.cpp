// Which primitives the deferred characters shade from a surface
// (ShaderVariant::deferrable) and the one program that shades each material's
// pixels (ShaderVariant::shadingFromSurface). A surface holds uv, the base colour's
// level of detail, the normal and the distance (common/surface.glsl): a variant that
// reads any other interpolated or textured input, discards, or is itself a surface
// pass must be drawn forward. Meshes of one material, however they deform, share
// the shading program.
#include <gtest/gtest.h>

#include "render/model_renderer.h"

using namespace engine;

namespace {

ShaderVariant skinnedTextured() {
  ShaderVariant v;
  v.influences = 4;
  v.textured = true;
  v.matte = true;
  v.oneSided = true;
  return v;
}

TEST(SurfaceVariant, TheBaseColourTextureAndDeformationAreDeferrable) {
  EXPECT_TRUE(ShaderVariant{}.deferrable());
  EXPECT_TRUE(skinnedTextured().deferrable());
  ShaderVariant morphed = skinnedTextured();
  morphed.morph = true;
  morphed.mode = SkinMode::DualQuat;
  morphed.nearSunOnly = true;
  EXPECT_TRUE(morphed.deferrable());
}

TEST(SurfaceVariant, EveryOtherInputKeepsTheForwardDraw) {
  bool ShaderVariant::*const inputs[] = {&ShaderVariant::depthOnly,       &ShaderVariant::normalMap,
                                         &ShaderVariant::metallicRoughnessTexture,
                                         &ShaderVariant::emissiveTexture, &ShaderVariant::occlusion,
                                         &ShaderVariant::alphaMask,       &ShaderVariant::uvTransform,
                                         &ShaderVariant::unlit,           &ShaderVariant::vertexColor,
                                         &ShaderVariant::layers,          &ShaderVariant::layerTextures,
                                         &ShaderVariant::transmission,    &ShaderVariant::clearcoatNormal,
                                         &ShaderVariant::sheen,           &ShaderVariant::anisotropy,
                                         &ShaderVariant::iridescence};
  for (bool ShaderVariant::*input : inputs) {
    ShaderVariant v = skinnedTextured();
    v.*input = true;
    EXPECT_FALSE(v.deferrable()) << v.describe();
  }
  for (ShaderVariant::Surface surface : {ShaderVariant::Surface::Out, ShaderVariant::Surface::In}) {
    ShaderVariant v = skinnedTextured();
    v.surface = surface;
    EXPECT_FALSE(v.deferrable()) << v.describe();
  }
}

TEST(SurfaceVariant, OneShadingProgramForAMaterialHoweverItsMeshesDeform) {
  const ShaderVariant shading = skinnedTextured().shadingFromSurface();
  EXPECT_EQ(shading.surface, ShaderVariant::Surface::In);
  EXPECT_TRUE(shading.textured);
  EXPECT_TRUE(shading.matte);  // the material's, kept
  EXPECT_EQ(shading.influences, 0);
  EXPECT_FALSE(shading.oneSided);  // the surface holds the lit side's normal
  ShaderVariant other = skinnedTextured();
  other.influences = 8;
  other.mode = SkinMode::DualQuat;
  other.morph = true;
  other.oneSided = false;
  other.nearSunOnly = true;
  EXPECT_EQ(other.shadingFromSurface(), shading);
  ShaderVariant untextured = skinnedTextured();
  untextured.textured = false;
  EXPECT_NE(untextured.shadingFromSurface(), shading);
  EXPECT_EQ(shading.describe(), "static+textured+matte+fromsurface");
}

}  // namespace
