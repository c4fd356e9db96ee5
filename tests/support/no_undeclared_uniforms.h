#pragma once
// Registered once in every binary that includes it: after its tests, no Program was
// asked to set a uniform that none of its stages declares (gl::undeclaredUniformsSet:
// a misspelt or stale name, which GL would ignore silently).
#include <gtest/gtest.h>

#include "gl/shader.h"

namespace engine::test {

class NoUndeclaredUniforms : public ::testing::Environment {
 public:
  void TearDown() override {
    for (const auto& entry : gl::undeclaredUniformsSet()) ADD_FAILURE() << "set but never declared: " << entry;
  }
};

inline ::testing::Environment* const kNoUndeclaredUniforms =
    ::testing::AddGlobalTestEnvironment(new NoUndeclaredUniforms);

}  // namespace engine::test
