// Nodes: the tree and the scene drawn, each node's weights, skins, cameras,
// KHR_lights_punctual lights and EXT_mesh_gpu_instancing instances.
#include <algorithm>
#include <cmath>
#include <optional>

#include "asset/gltf_loader_impl.h"
#include "core/math.h"

namespace engine::gltf_loader {

Status Converter::convertNodes() {
  std::size_t count = gltf_.nodes.size();
  out_.nodes.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (Status s = convertNode(i); !s) return s;
  }
  if (Status s = checkTree(); !s) return s;
  return findSceneRoots();
}

Status Converter::convertNode(std::size_t i) {
  const tinygltf::Node& src = gltf_.nodes[i];
  NodeData& node = out_.nodes[i];
  std::string name = "node " + str(i);
  node.name = src.name;
  if (src.mesh != -1 && !validIndex(src.mesh, gltf_.meshes.size()))
    return error(name + ": mesh " + str(src.mesh) + " does not exist");
  if (src.skin != -1 && !validIndex(src.skin, gltf_.skins.size()))
    return error(name + ": skin " + str(src.skin) + " does not exist");
  node.mesh = src.mesh;
  node.skin = src.skin;
  for (int child : src.children) {
    if (!validIndex(child, gltf_.nodes.size()))
      return error(name + ": child " + str(child) + " does not exist");
    std::size_t c = static_cast<std::size_t>(child);
    if (c == i) return error(name + ": is its own child (cycle)");
    if (out_.nodes[c].parent != -1)
      return error("node " + str(c) + " has two parents (nodes " + str(out_.nodes[c].parent) +
                   " and " + str(i) + ")");
    out_.nodes[c].parent = static_cast<int>(i);
    node.children.push_back(child);
  }
  return readNodeTransform(src, node, name);
}

Status Converter::readNodeTransform(const tinygltf::Node& src, NodeData& node, const std::string& name) {
  auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (!finite(src.matrix) || !finite(src.translation) || !finite(src.rotation) || !finite(src.scale))
    return error(name + ": transform has a NaN or infinite value");
  if (src.matrix.size() == 16) {
    glm::mat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = static_cast<float>(src.matrix[static_cast<std::size_t>(c * 4 + r)]);
    Srt srt = decompose(m);
    node.translation = srt.translation;
    node.rotation = srt.rotation;
    node.scale = srt.scale;
    return Ok{};
  }
  if (!src.matrix.empty()) return error(name + ": matrix must have 16 numbers");
  if (src.translation.size() == 3)
    node.translation = glm::vec3(src.translation[0], src.translation[1], src.translation[2]);
  if (src.scale.size() == 3) node.scale = glm::vec3(src.scale[0], src.scale[1], src.scale[2]);
  if (src.rotation.size() == 4)
    node.rotation = safeNormalize(glm::quat(static_cast<float>(src.rotation[3]), static_cast<float>(src.rotation[0]),
                                            static_cast<float>(src.rotation[1]), static_cast<float>(src.rotation[2])));
  return Ok{};
}

// With at most one parent per node (checked above), a node that cannot be
// reached from a root sits on a cycle.
Status Converter::checkTree() {
  std::vector<char> reached(out_.nodes.size(), 0);
  std::vector<int> stack;
  for (std::size_t i = 0; i < out_.nodes.size(); ++i)
    if (out_.nodes[i].parent == -1) stack.push_back(static_cast<int>(i));
  while (!stack.empty()) {
    int n = stack.back();
    stack.pop_back();
    reached[static_cast<std::size_t>(n)] = 1;
    for (int c : out_.nodes[static_cast<std::size_t>(n)].children) stack.push_back(c);
  }
  for (std::size_t i = 0; i < reached.size(); ++i)
    if (!reached[i]) return error("node " + str(i) + ": is part of a cycle in the node tree");
  return Ok{};
}

// The scene drawn: the one asked for (viewer --scene), else the file's default,
// else its first; a file without scenes (or an empty one) draws every root.
Status Converter::findSceneRoots() {
  if (scene_ >= 0 && !validIndex(scene_, gltf_.scenes.size()))
    return error("scene " + str(scene_) + " does not exist (the file has " + str(gltf_.scenes.size()) + ")");
  const int scene = scene_ >= 0 ? scene_ : gltf_.defaultScene >= 0 ? gltf_.defaultScene : 0;
  if (validIndex(scene, gltf_.scenes.size())) {
    for (int n : gltf_.scenes[static_cast<std::size_t>(scene)].nodes)
      if (validIndex(n, out_.nodes.size()) && out_.nodes[static_cast<std::size_t>(n)].parent == -1)
        out_.sceneRoots.push_back(n);
    if (!out_.sceneRoots.empty()) {
      out_.scene = scene;
      return Ok{};
    }
  }
  for (std::size_t i = 0; i < out_.nodes.size(); ++i)
    if (out_.nodes[i].parent == -1) out_.sceneRoots.push_back(static_cast<int>(i));
  return Ok{};
}

// Nodes outside the scene drawn keep their place in the tree and their animation,
// but draw, light and look through nothing (MultipleScenes' other scene's mesh
// would otherwise lie in this one's).
void Converter::leaveOutOtherScenes() {
  if (out_.scene < 0) return;
  std::vector<char> inScene(out_.nodes.size(), 0);
  std::vector<int> stack(out_.sceneRoots.begin(), out_.sceneRoots.end());
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    inScene[static_cast<std::size_t>(n)] = 1;
    for (int c : out_.nodes[static_cast<std::size_t>(n)].children) stack.push_back(c);
  }
  for (std::size_t i = 0; i < out_.nodes.size(); ++i) {
    if (inScene[i]) continue;
    NodeData& node = out_.nodes[i];
    node.mesh = -1;
    node.instances.clear();
    node.light = -1;
    node.camera = -1;
  }
}

// Each node's default weights: its own (checked against its mesh), else the mesh's.
Status Converter::resolveNodeWeights() {
  for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
    NodeData& node = out_.nodes[n];
    const std::vector<double>& own = gltf_.nodes[n].weights;
    const std::string name = "node " + str(n);
    if (node.mesh < 0) {
      if (!own.empty()) return error(name + ": has weights but no mesh");
      continue;
    }
    const MeshData& mesh = out_.meshes[static_cast<std::size_t>(node.mesh)];
    if (own.empty()) {
      node.morphWeights = mesh.morphWeights;
      continue;
    }
    auto weights = readWeightList(own, targetCount(mesh), name + " (mesh " + str(node.mesh) + ")");
    if (!weights) return weights.error();
    node.morphWeights = std::move(weights).value();
  }
  return Ok{};
}

Status Converter::convertSkins() {
  for (std::size_t s = 0; s < gltf_.skins.size(); ++s) {
    const tinygltf::Skin& src = gltf_.skins[s];
    std::string name = "skin " + str(s);
    SkinData skin;
    skin.name = src.name;
    if (src.joints.empty()) return error(name + ": has no joints");
    for (std::size_t j = 0; j < src.joints.size(); ++j)
      if (!validIndex(src.joints[j], out_.nodes.size()))
        return error(name + ": joint " + str(j) + " has no node (node " + str(src.joints[j]) + ")");
    skin.joints = src.joints;
    skin.skeleton = validIndex(src.skeleton, out_.nodes.size()) ? src.skeleton : -1;
    skin.inverseBinds.assign(src.joints.size(), glm::mat4(1.0f));
    if (src.inverseBindMatrices >= 0) {
      auto m = readFloats(src.inverseBindMatrices, 16, 0, name + " inverseBindMatrices");
      if (!m) return m.error();
      if (m->size() / 16 < src.joints.size())
        return error(name + " inverseBindMatrices: " + str(m->size() / 16) + " matrices for " +
                     str(src.joints.size()) + " joints");
      for (std::size_t j = 0; j < src.joints.size(); ++j)
        for (int c = 0; c < 16; ++c) skin.inverseBinds[j][c / 4][c % 4] = (*m)[j * 16 + static_cast<std::size_t>(c)];
    }
    out_.skins.push_back(std::move(skin));
  }
  return Ok{};
}

// A vertex that names a joint past its skin's list would read outside the palette.
Status Converter::checkSkinnedMeshes() {
  for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
    const NodeData& node = out_.nodes[n];
    if (node.mesh < 0 || node.skin < 0) continue;
    std::size_t jointCount = out_.skins[static_cast<std::size_t>(node.skin)].joints.size();
    const MeshData& mesh = out_.meshes[static_cast<std::size_t>(node.mesh)];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const PrimitiveData& prim = mesh.primitives[p];
      for (std::size_t i = 0; i < prim.joints.size(); ++i)
        if (prim.joints[i] >= jointCount && prim.weights[i] > 0.0f)
          return error("node " + str(n) + ": mesh " + str(node.mesh) + " primitive " + str(p) +
                       ": vertex " + str(i / static_cast<std::size_t>(prim.influences)) + " uses joint " +
                       str(static_cast<std::size_t>(prim.joints[i])) + " past skin " + str(node.skin) +
                       " of " + str(jointCount) + " joints");
    }
  }
  return Ok{};
}

// The file's cameras, then the node of each that places it.
Status Converter::convertCameras() {
  for (std::size_t i = 0; i < gltf_.cameras.size(); ++i) {
    auto camera = convertCamera(gltf_.cameras[i], labelled("camera", i, gltf_.cameras[i].name));
    if (!camera) return camera.error();
    out_.cameras.push_back(std::move(camera).value());
  }
  for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
    const int camera = gltf_.nodes[n].camera;
    if (camera == -1) continue;
    if (!validIndex(camera, out_.cameras.size()))
      return error("node " + str(n) + ": camera " + str(camera) + " does not exist (" + str(out_.cameras.size()) + " cameras)");
    out_.nodes[n].camera = camera;
  }
  return Ok{};
}

// One camera; an error names it and the value out of glTF's range.
Result<CameraData> Converter::convertCamera(const tinygltf::Camera& src, const std::string& where) {
  CameraData camera;
  camera.name = src.name;
  camera.perspective = src.type == "perspective";
  if (!camera.perspective && src.type != "orthographic")
    return error(where + ": type \"" + src.type + "\" is not perspective or orthographic");
  if (camera.perspective) {
    const tinygltf::PerspectiveCamera& p = src.perspective;
    if (!(p.yfov > 0.0 && p.yfov < 3.14159265358979)) return error(where + ": yfov must be in (0, pi)");
    if (!(p.znear > 0.0 && std::isfinite(p.znear))) return error(where + ": znear must be > 0");
    if (!(p.zfar == 0.0 || (p.zfar > p.znear && std::isfinite(p.zfar)))) return error(where + ": zfar must be > znear");
    if (!(p.aspectRatio >= 0.0 && std::isfinite(p.aspectRatio))) return error(where + ": aspectRatio must be > 0");
    camera.yfov = float(p.yfov);
    camera.znear = float(p.znear);
    camera.zfar = float(p.zfar);
    camera.aspectRatio = float(p.aspectRatio);
    return camera;
  }
  const tinygltf::OrthographicCamera& o = src.orthographic;
  if (!(o.xmag != 0.0 && o.ymag != 0.0 && std::isfinite(o.xmag) && std::isfinite(o.ymag)))
    return error(where + ": xmag and ymag must be finite and not 0");
  if (!(o.znear >= 0.0 && o.zfar > o.znear && std::isfinite(o.zfar))) return error(where + ": needs 0 <= znear < zfar");
  camera.xmag = float(o.xmag);
  camera.ymag = float(o.ymag);
  camera.znear = float(o.znear);
  camera.zfar = float(o.zfar);
  return camera;
}

// KHR_lights_punctual: the file's lights (tinygltf parses the list), then the
// node of each that places it.
Status Converter::convertLights() {
  for (std::size_t i = 0; i < gltf_.lights.size(); ++i) {
    auto light = convertLight(gltf_.lights[i], labelled("light", i, gltf_.lights[i].name));
    if (!light) return light.error();
    out_.lights.push_back(std::move(light).value());
  }
  for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
    auto ext = gltf_.nodes[n].extensions.find("KHR_lights_punctual");
    if (ext == gltf_.nodes[n].extensions.end()) continue;
    const std::string where = "node " + str(n) + ": KHR_lights_punctual";
    if (!ext->second.IsObject() || !ext->second.Has("light") || !ext->second.Get("light").IsInt())
      return error(where + ": needs a \"light\" index");
    const int light = ext->second.Get("light").GetNumberAsInt();
    if (!validIndex(light, out_.lights.size()))
      return error(where + ": light " + str(light) + " does not exist (" + str(out_.lights.size()) + " lights)");
    out_.nodes[n].light = light;
  }
  return Ok{};
}

Result<PunctualLightData> Converter::convertLight(const tinygltf::Light& src, const std::string& where) {
  PunctualLightData light;
  light.name = src.name;
  if (src.type == "directional") light.type = PunctualType::Directional;
  else if (src.type == "point") light.type = PunctualType::Point;
  else if (src.type == "spot") light.type = PunctualType::Spot;
  else return error(where + ": type \"" + src.type + "\" is not directional, point or spot");
  if (!src.color.empty()) {
    if (src.color.size() != 3) return error(where + ": color must have 3 numbers");
    for (int c = 0; c < 3; ++c) {
      const double v = src.color[std::size_t(c)];
      if (!std::isfinite(v) || v < 0.0) return error(where + ": color must be finite and >= 0");
      light.color[c] = float(v);
    }
  }
  if (!std::isfinite(src.intensity) || src.intensity < 0.0 || src.intensity > 1e30)
    return error(where + ": intensity must be a finite number >= 0");
  light.intensity = float(src.intensity);
  if (!std::isfinite(src.range) || src.range < 0.0) return error(where + ": range must be a finite number >= 0");
  light.range = float(src.range);
  if (light.type == PunctualType::Spot) {
    const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
    // glTF asks for inner < outer; equal cones are a sharp edge, which every renderer
    // draws (common/spot_cone.glsl), so they are taken. pi/2 as a float (what an
    // exporter working in float writes) is a hair above pi/2, and is taken as pi/2.
    constexpr double kHalfPi = 1.5707963267948966;
    if (!(inner >= 0.0 && inner <= outer && outer <= kHalfPi + 1e-6))
      return error(where + ": spot.innerConeAngle and spot.outerConeAngle must be 0 <= inner <= outer <= pi/2");
    light.innerConeAngle = float(std::min(inner, kHalfPi));
    light.outerConeAngle = float(std::min(outer, kHalfPi));
  }
  return light;
}

// EXT_mesh_gpu_instancing on every node that has it.
Status Converter::convertInstancing() {
  for (std::size_t n = 0; n < out_.nodes.size(); ++n) {
    auto ext = gltf_.nodes[n].extensions.find("EXT_mesh_gpu_instancing");
    if (ext == gltf_.nodes[n].extensions.end()) continue;
    if (Status s = readInstancing(ext->second, n); !s) return s;
  }
  return Ok{};
}

// One instancing attribute (TRANSLATION, ROTATION or SCALE): `components` floats
// per instance, or nothing when the node does not give it. The count is checked
// against the other attributes' by the caller.
Result<std::optional<AccessorValues>> Converter::instancingAttribute(const tinygltf::Value& attributes, const char* semantic,
                                                                     int components, const std::string& where) const {
  if (!attributes.Has(semantic)) return std::optional<AccessorValues>{};
  const tinygltf::Value& id = attributes.Get(semantic);
  const std::string name = where + " " + semantic;
  if (!id.IsInt()) return error(name + ": must be an accessor index");
  // The instance limit before the values are read: a large sparse accessor costs
  // nothing in the file but 32 bytes per component once read.
  const int index = id.GetNumberAsInt();
  if (validIndex(index, gltf_.accessors.size()) && gltf_.accessors[std::size_t(index)].count > kMaxNodeInstances)
    return error(name + ": accessor " + str(index) + ": " + str(gltf_.accessors[std::size_t(index)].count) +
                 " instances, the limit is " + str(kMaxNodeInstances));
  auto values = readAccessor(gltf_, index, file_ + ": " + name);
  if (!values) return values.error();
  if (values->components != components)
    return error(name + ": accessor " + str(id.GetNumberAsInt()) + " has " + str(values->components) +
                 " components per element, expected " + str(components) + (components == 3 ? " (VEC3)" : " (VEC4)"));
  for (double v : values->values)
    if (!std::isfinite(v)) return error(name + ": accessor " + str(id.GetNumberAsInt()) + " has a NaN or infinite value");
  return std::optional<AccessorValues>(std::move(values).value());
}

// The node's instances: every attribute that is present must have the same count
// (the extension's rule); a missing one is the identity for that part.
Status Converter::readInstancing(const tinygltf::Value& ext, std::size_t n) {
  const std::string where = "node " + str(n) + ": EXT_mesh_gpu_instancing";
  if (!ext.IsObject() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
    return error(where + ": needs an \"attributes\" object");
  const tinygltf::Value& attributes = ext.Get("attributes");
  std::optional<AccessorValues> parts[3];
  const char* semantics[3] = {"TRANSLATION", "ROTATION", "SCALE"};
  const int components[3] = {3, 4, 3};
  std::size_t count = 0;
  for (int k = 0; k < 3; ++k) {
    auto part = instancingAttribute(attributes, semantics[k], components[k], where);
    if (!part) return part.error();
    parts[k] = std::move(part).value();
    if (!parts[k]) continue;
    if (count != 0 && parts[k]->count != count)
      return error(where + " " + semantics[k] + ": has " + str(parts[k]->count) + " instances, the other attributes " +
                   str(count));
    count = parts[k]->count;
  }
  if (count == 0) return error(where + ": has no TRANSLATION, ROTATION or SCALE accessor");
  NodeData& node = out_.nodes[n];
  if (node.mesh < 0) {
    warn(where + ": the node has no mesh; ignored");
    return Ok{};
  }
  if (node.skin >= 0) {
    // A skinned mesh is placed by its joints, not its node, so instance transforms
    // relative to the node have nothing to move; drawn once, skinned.
    warn(where + ": the node is skinned; drawn once, without its instances");
    return Ok{};
  }
  node.instances.reserve(count);
  for (std::size_t i = 0; i < count; ++i) node.instances.push_back(instanceMatrix(parts, i));
  return Ok{};
}

glm::mat4 Converter::instanceMatrix(const std::optional<AccessorValues> (&parts)[3], std::size_t i) {
  Srt srt;
  if (parts[0]) srt.translation = glm::vec3(float(parts[0]->at(i, 0)), float(parts[0]->at(i, 1)), float(parts[0]->at(i, 2)));
  if (parts[1])  // glTF x, y, z, w; glm's constructor takes w first
    srt.rotation = safeNormalize(glm::quat(float(parts[1]->at(i, 3)), float(parts[1]->at(i, 0)),
                                           float(parts[1]->at(i, 1)), float(parts[1]->at(i, 2))));
  if (parts[2]) srt.scale = glm::vec3(float(parts[2]->at(i, 0)), float(parts[2]->at(i, 1)), float(parts[2]->at(i, 2)));
  return toMatrix(srt);
}

}  // namespace engine::gltf_loader
