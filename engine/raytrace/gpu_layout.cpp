#include "raytrace/gpu_layout.h"

#include <algorithm>
#include <bit>

namespace engine::rt {
namespace {

// A group's reference moved into the shared arrays: interior nodes by nodeBase,
// leaves' Triangle4 blocks by leafBase; the count bits and kNoChild stay.
std::uint32_t rebase(std::uint32_t ref, std::uint32_t nodeBase, std::uint32_t leafBase) {
  if (ref == Bvh::kNoChild) return ref;
  if (!Bvh::isLeaf(ref)) return ref + nodeBase;
  return Bvh::leafRef(Bvh::leafIndex(ref) + leafBase, Bvh::leafCount(ref));
}

// Levels of nodes below `ref`, counting the leaf: what bounds a traversal's stack.
int levels(const Bvh::View& view, std::uint32_t ref) {
  if (ref == Bvh::kNoChild || Bvh::isLeaf(ref)) return 1;
  int deepest = 0;
  for (std::uint32_t child : view.nodes[ref].child) deepest = std::max(deepest, levels(view, child));
  return 1 + deepest;
}

void appendGroup(const RtScene& scene, int group, GpuSceneLayout& out) {
  const Bvh& bvh = scene.bvh(group);
  const Bvh::View view = bvh.view();
  const auto nodeBase = std::uint32_t(out.nodes.size());
  const auto leafBase = std::uint32_t(out.leaves.size());
  const auto triangleBase = std::uint32_t(out.triangles.size());
  out.firstTriangle.push_back(triangleBase);
  for (std::size_t i = 0; i < bvh.nodeCount(); ++i) {
    const Bvh::Node& node = view.nodes[i];
    GpuNode& g = out.nodes.emplace_back();
    for (int row = 0; row < 6; ++row) {
      for (int half = 0; half < 2; ++half) {
        g.box[2 * row + half] = glm::vec4(node.box[row][4 * half], node.box[row][4 * half + 1],
                                          node.box[row][4 * half + 2], node.box[row][4 * half + 3]);
      }
    }
    for (int k = 0; k < Bvh::kWidth; ++k) g.child[k / 4][k % 4] = rebase(node.child[k], nodeBase, leafBase);
  }
  for (std::size_t i = 0; i < bvh.leafCount(); ++i) {
    const Bvh::Triangle4& leaf = view.leaves[i];
    GpuLeaf& g = out.leaves.emplace_back();
    for (int v = 0; v < 3; ++v) {
      for (int axis = 0; axis < 3; ++axis) {
        g.p[3 * v + axis] = glm::vec4(leaf.p[v][axis][0], leaf.p[v][axis][1], leaf.p[v][axis][2], leaf.p[v][axis][3]);
      }
    }
    for (int lane = 0; lane < 4; ++lane) {
      const std::uint32_t local = view.order[4 * i + std::size_t(lane)];
      out.order.push_back(local == Bvh::kNoChild ? local : triangleBase + local);
    }
  }
  const std::vector<std::uint32_t>& meshOf = scene.groupTriangleMeshes(group);
  for (std::size_t t = 0; t < meshOf.size(); ++t) {
    const RtMesh& mesh = scene.meshes()[meshOf[t]];
    const std::size_t first = 3 * (t - scene.meshFirstTriangle(MeshId(meshOf[t])));
    GpuTriangle& g = out.triangles.emplace_back();
    for (int v = 0; v < 3 && !mesh.normals.empty(); ++v) g.n[v] = glm::vec4(mesh.normals[mesh.indices[first + std::size_t(v)]], 0.0f);
    g.n[0].w = float(mesh.material);
    g.n[1].w = mesh.normals.empty() ? 0.0f : 1.0f;
  }
  if (bvh.empty()) return;
  const Bounds3f b = bvh.bounds();
  out.instances.push_back(GpuInstance{glm::vec4(b.min, 0.0f), glm::vec4(b.max, 0.0f),
                                      glm::uvec4(rebase(view.root, nodeBase, leafBase), 0, 0, 0)});
  out.depth = std::max(out.depth, levels(view, view.root));
}

}  // namespace

GpuSceneLayout flattenScene(const RtScene& scene) {
  GpuSceneLayout out;
  for (int g = 0; g < scene.groupCount(); ++g) appendGroup(scene, g, out);
  for (const Sphere<float>& s : scene.floatSpheres()) {
    out.spheres.push_back(GpuSphere{glm::vec4(s.center, s.radius), glm::ivec4(s.material, 0, 0, 0)});
  }
  for (std::size_t i = 0; i < scene.floatPlanes().size(); ++i) {
    const Plane<float>& p = scene.floatPlanes()[i];
    const RtScene::PlaneSquare& q = scene.planeSquare(i);
    out.planes.push_back(GpuPlane{glm::vec4(p.normal, p.d), glm::vec4(glm::vec3(q.point), float(q.extent)),
                                  glm::vec4(glm::vec3(q.axisU), float(p.material)), glm::vec4(glm::vec3(q.axisV), 0.0f)});
  }
  return out;
}

}  // namespace engine::rt
