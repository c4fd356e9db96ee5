#include "gputrace/gpu_layout.h"

#include <algorithm>
#include <limits>

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

// The 4-wide tree made from a group's 8-wide one, depth first (a parent before its
// children, as the CPU's).
class Narrower {
 public:
  Narrower(const Bvh::View& view, std::uint32_t leafBase, std::vector<GpuNode4>& out)
      : view_(view), leafBase_(leafBase), out_(out) {}

  // The 4-wide reference for a CPU reference; its levels below go to depth.
  std::uint32_t convert(std::uint32_t ref, int& depth) {
    depth = 1;
    if (ref == Bvh::kNoChild || Bvh::isLeaf(ref)) return rebase(ref, 0, leafBase_);
    const Bvh::Node& node = view_.nodes[ref];
    std::vector<int> kids;
    for (int k = 0; k < Bvh::kWidth; ++k) {
      if (node.child[k] != Bvh::kNoChild) kids.push_back(k);
    }
    // Past four children, the first ones pair up, neighbours with neighbours.
    const int pairs = std::max(0, int(kids.size()) - 4);
    const auto index = std::uint32_t(out_.size());
    out_.push_back(empty());
    int slot = 0;
    for (std::size_t i = 0; i < kids.size(); ++slot) {
      int below = 0;
      Bounds3f box = childBox(node, kids[i]);
      std::uint32_t child;
      if (slot < pairs) {
        box.extend(childBox(node, kids[i + 1]));
        child = pair(node, kids[i], kids[i + 1], below);
        i += 2;
      } else {
        child = convert(node.child[kids[i]], below);
        i += 1;
      }
      set(out_[index], slot, box, child);
      depth = std::max(depth, 1 + below);
    }
    return index;
  }

 private:
  static GpuNode4 empty() {
    GpuNode4 n;
    for (int row = 0; row < 6; ++row) n.box[row] = glm::vec4(row < 3 ? 1.0f : -1.0f) * std::numeric_limits<float>::infinity();
    n.child = glm::uvec4(Bvh::kNoChild);
    return n;
  }
  static Bounds3f childBox(const Bvh::Node& node, int k) {
    Bounds3f b;
    for (int axis = 0; axis < 3; ++axis) {
      b.min[axis] = node.box[axis][k];
      b.max[axis] = node.box[3 + axis][k];
    }
    return b;
  }
  static void set(GpuNode4& n, int slot, const Bounds3f& b, std::uint32_t child) {
    for (int axis = 0; axis < 3; ++axis) {
      n.box[axis][slot] = b.min[axis];
      n.box[3 + axis][slot] = b.max[axis];
    }
    n.child[slot] = child;
  }
  // Two children of a CPU node under a 4-wide node of their own.
  std::uint32_t pair(const Bvh::Node& node, int a, int b, int& depth) {
    const auto index = std::uint32_t(out_.size());
    out_.push_back(empty());
    depth = 1;
    int slot = 0;
    for (const int k : {a, b}) {
      int below = 0;
      const std::uint32_t child = convert(node.child[k], below);
      set(out_[index], slot++, childBox(node, k), child);
      depth = std::max(depth, 1 + below);
    }
    return index;
  }

  const Bvh::View& view_;
  std::uint32_t leafBase_;
  std::vector<GpuNode4>& out_;
};

// The triangle's attributes (GpuSceneLayout::triangleAttributes) after `out`'s.
void appendAttributes(const RtMesh& mesh, std::size_t first, bool uvs, bool colors, std::vector<glm::vec4>& out) {
  for (int v = 0; v < 3 && uvs; ++v) {
    const std::uint32_t i = mesh.indices[first + std::size_t(v)];
    const glm::vec2 uv0 = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[i];
    out.emplace_back(uv0, mesh.uvs1.empty() ? uv0 : mesh.uvs1[i]);
  }
  for (int v = 0; v < 3 && colors; ++v) {
    out.push_back(mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[mesh.indices[first + std::size_t(v)]]);
  }
}

void appendGroup(const RtScene& scene, int group, GpuSceneLayout& out) {
  const Bvh& bvh = scene.bvh(group);
  const Bvh::View view = bvh.view();
  const auto nodeBase = std::uint32_t(out.nodes.size());
  const auto leafBase = std::uint32_t(out.leaves.size());
  const auto triangleBase = std::uint32_t(out.triangles.size());
  out.firstTriangle.push_back(triangleBase);
  for (std::size_t i = 0; i < bvh.nodeCount() && out.width == 8; ++i) {
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
    g.n[2].w = mesh.colors.empty() ? 0.0f : 1.0f;
    appendAttributes(mesh, first, out.hasUvs, out.hasColors, out.triangleAttributes);
  }
  if (bvh.empty()) return;
  const Bounds3f b = bvh.bounds();
  std::uint32_t root = rebase(view.root, nodeBase, leafBase);
  int depth = levels(view, view.root);
  if (out.width == 4) root = Narrower(view, leafBase, out.nodes4).convert(view.root, depth);
  out.instances.push_back(GpuInstance{glm::vec4(b.min, 0.0f), glm::vec4(b.max, 0.0f), glm::uvec4(root, 0, 0, 0)});
  out.depth = std::max(out.depth, depth);
}

}  // namespace

GpuSceneLayout flattenScene(const RtScene& scene, int width) {
  GpuSceneLayout out;
  out.width = width == 4 ? 4 : 8;
  out.hasColors = std::any_of(scene.meshes().begin(), scene.meshes().end(), [](const RtMesh& m) { return !m.colors.empty(); });
  // Only what a material reads (a texture, or an anisotropic lobe's uv gradient): the
  // box meshes of a scene file have uvs.
  const auto& materials = scene.materials();
  const bool anisotropic =
      std::any_of(materials.begin(), materials.end(), [](const MaterialDesc& m) { return m.layers.anisotropy > 0.0f; });
  out.hasUvs = (scene.hasTextures() || anisotropic) && std::any_of(scene.meshes().begin(), scene.meshes().end(), [](const RtMesh& m) { return !m.uvs.empty() || !m.uvs1.empty(); });
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

namespace {

// Each of the group's meshes' first vertex in the group's array (meshes in the order
// their triangles come); -1 for meshes of other groups.
std::vector<std::int64_t> vertexBases(const RtScene& scene, int group, std::uint32_t& count) {
  std::vector<std::int64_t> base(scene.meshes().size(), -1);
  count = 0;
  for (const std::uint32_t mesh : scene.groupTriangleMeshes(group)) {
    if (base[mesh] >= 0) continue;
    base[mesh] = count;
    count += std::uint32_t(scene.meshes()[mesh].positions.size());
  }
  return base;
}

// The group's triangle (local index) as its three vertices in the group's array.
glm::uvec4 corners(const RtScene& scene, int group, const std::vector<std::int64_t>& base, std::uint32_t triangle) {
  const std::uint32_t mesh = scene.groupTriangleMeshes(group)[triangle];
  const RtMesh& m = scene.meshes()[mesh];
  const std::size_t first = 3 * std::size_t(triangle - scene.meshFirstTriangle(MeshId(mesh)));
  const auto at = [&](int v) { return std::uint32_t(base[mesh] + m.indices[first + std::size_t(v)]); };
  return glm::uvec4(at(0), at(1), at(2), m.normals.empty() ? 0u : 1u);
}

// Every node below `ref` by its depth (the first level 0).
void nodesByDepth(const GpuSceneLayout& layout, std::uint32_t ref, std::size_t depth,
                  std::vector<std::vector<std::uint32_t>>& out) {
  if (ref == Bvh::kNoChild || Bvh::isLeaf(ref)) return;
  if (out.size() <= depth) out.resize(depth + 1);
  out[depth].push_back(ref);
  if (layout.width == 4) {
    for (int k = 0; k < 4; ++k) nodesByDepth(layout, layout.nodes4[ref].child[k], depth + 1, out);
  } else {
    for (int k = 0; k < 8; ++k) nodesByDepth(layout, layout.nodes[ref].child[k / 4][k % 4], depth + 1, out);
  }
}

}  // namespace

GpuRefitPlan refitPlan(const RtScene& scene, const GpuSceneLayout& layout, int group) {
  GpuRefitPlan plan;
  const std::vector<std::int64_t> base = vertexBases(scene, group, plan.vertexCount);
  plan.firstTriangle = layout.firstTriangle[std::size_t(group)];
  const auto triangles = std::uint32_t(scene.groupTriangleMeshes(group).size());
  for (std::uint32_t t = 0; t < triangles; ++t) plan.triangleCorners.push_back(corners(scene, group, base, t));
  for (int g = 0; g < group; ++g) {
    plan.firstLeaf += std::uint32_t(scene.bvh(g).leafCount());
    if (!scene.bvh(g).empty()) ++plan.instance;
  }
  if (scene.bvh(group).empty()) {
    plan.instance = -1;
    return plan;
  }
  ++plan.instance;
  for (std::size_t slot = 0; slot < 4 * scene.bvh(group).leafCount(); ++slot) {
    const std::uint32_t id = layout.order[4 * plan.firstLeaf + slot];
    plan.leafCorners.push_back(id == Bvh::kNoChild ? glm::uvec4(0) : corners(scene, group, base, id - plan.firstTriangle));
    if (id != Bvh::kNoChild) plan.leafCorners.back().w = 1;
  }
  nodesByDepth(layout, layout.instances[std::size_t(plan.instance)].root.x, 0, plan.levels);
  std::reverse(plan.levels.begin(), plan.levels.end());
  return plan;
}

}  // namespace engine::rt
