#pragma once
// The BVH traversal's compiles (Bvh::Isa) that this CPU runs, each in turn, for the
// tests that hold them all to the same answers (bvh_test.cpp, bvh_packet_test.cpp);
// afterwards the CPU's best again. Those the CPU lacks are left out.
#include <initializer_list>

#include <gtest/gtest.h>

#include "raytrace/bvh.h"

template <typename Check>
void forEachIsa(std::initializer_list<engine::rt::Bvh::Isa> isas, Check check) {
  using engine::rt::Bvh;
  const Bvh::Isa best = Bvh::isa();
  for (const Bvh::Isa isa : isas) {
    Bvh::setIsa(isa);
    if (Bvh::isa() != isa) continue;
    SCOPED_TRACE(Bvh::isaName(isa));
    check();
  }
  Bvh::setIsa(best);
}
