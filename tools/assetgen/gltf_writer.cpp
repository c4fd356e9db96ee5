#include "gltf_writer.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>

#include "gltf_buffer.h"

namespace assetgen {

namespace {

// Interleaved vertex: position, normal, uv, joints (4 bytes), weights.
constexpr int kVertexStride = 12 + 12 + 8 + 4 + 16;

template <typename T>
void appendBytes(std::vector<std::uint8_t>& out, const T& value) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
  out.insert(out.end(), p, p + sizeof(T));
}

Json nodesJson(const Character& character) {
  Json nodes = Json::array();
  for (const Joint& joint : character.joints) {
    const glm::vec3 parent =
        joint.parent < 0 ? glm::vec3(0.0f) : character.joints[joint.parent].bindPosition;
    nodes.push_back({{"name", joint.name}, {"translation", vec3Json(joint.bindPosition - parent)}});
  }
  for (size_t i = 0; i < character.joints.size(); ++i) {
    const int parent = character.joints[i].parent;
    if (parent >= 0) nodes[parent]["children"].push_back(i);
  }
  // The skinned mesh node is a root of its own: the joints alone place the vertices.
  nodes.push_back({{"name", character.name}, {"mesh", 0}, {"skin", 0}});
  return nodes;
}

Json primitiveJson(const Character& character, BufferBuilder& buffer) {
  std::vector<std::uint8_t> bytes;
  std::vector<float> positions;
  for (const Vertex& v : character.vertices) {
    appendBytes(bytes, v.position);
    appendBytes(bytes, v.normal);
    appendBytes(bytes, v.uv);
    appendBytes(bytes, v.joints);
    appendBytes(bytes, v.weights);
    positions.insert(positions.end(), {v.position.x, v.position.y, v.position.z});
  }
  const int view = buffer.addView(bytes, kArrayBuffer, kVertexStride);
  const size_t count = character.vertices.size();
  Json bounds = {{"min", Json::array()}, {"max", Json::array()}};
  for (int c = 0; c < 3; ++c) {
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (const Vertex& v : character.vertices) {
      lo = std::min(lo, v.position[c]);
      hi = std::max(hi, v.position[c]);
    }
    bounds["min"].push_back(lo);
    bounds["max"].push_back(hi);
  }
  Json attributes;
  attributes["POSITION"] = buffer.addAccessor(view, 0, kFloat, count, "VEC3", bounds);
  attributes["NORMAL"] = buffer.addAccessor(view, 12, kFloat, count, "VEC3");
  attributes["TEXCOORD_0"] = buffer.addAccessor(view, 24, kFloat, count, "VEC2");
  attributes["JOINTS_0"] = buffer.addAccessor(view, 32, kUnsignedByte, count, "VEC4");
  attributes["WEIGHTS_0"] = buffer.addAccessor(view, 36, kFloat, count, "VEC4");

  std::vector<std::uint8_t> indexBytes;
  for (std::uint16_t index : character.indices) appendBytes(indexBytes, index);
  const int indexView = buffer.addView(indexBytes, kElementArrayBuffer, 0);
  const int indices =
      buffer.addAccessor(indexView, 0, kUnsignedShort, character.indices.size(), "SCALAR");
  return {{"attributes", attributes}, {"indices", indices}, {"material", 0}, {"mode", 4}};
}

Json skinJson(const Character& character, BufferBuilder& buffer) {
  // Bind rotations are the identity: each inverse bind is a translation by -position.
  std::vector<float> matrices;
  for (const Joint& joint : character.joints) {
    const glm::vec3 t = -joint.bindPosition;
    matrices.insert(matrices.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, t.x, t.y, t.z, 1});
  }
  Json joints = Json::array();
  for (size_t i = 0; i < character.joints.size(); ++i) joints.push_back(i);
  return {{"name", character.name + "_skin"},
          {"inverseBindMatrices", buffer.addFloats(matrices, 16, "MAT4", false)},
          {"joints", joints},
          {"skeleton", 0}};
}

const char* pathName(engine::AnimPath path) {
  switch (path) {
    case engine::AnimPath::Translation: return "translation";
    case engine::AnimPath::Rotation: return "rotation";
    default: return "scale";
  }
}

const char* interpolationName(engine::Interpolation interpolation) {
  switch (interpolation) {
    case engine::Interpolation::Step: return "STEP";
    case engine::Interpolation::CubicSpline: return "CUBICSPLINE";
    default: return "LINEAR";
  }
}

Json animationJson(const Clip& clip, BufferBuilder& buffer) {
  Json samplers = Json::array(), channels = Json::array();
  // Channels keyed at the same times share one input accessor.
  std::map<std::vector<float>, int> inputs;
  for (const Channel& channel : clip.channels) {
    auto input = inputs.find(channel.times);
    if (input == inputs.end()) {
      input =
          inputs.emplace(channel.times, buffer.addFloats(channel.times, 1, "SCALAR", true)).first;
    }
    const bool rotation = channel.path == engine::AnimPath::Rotation;
    std::vector<float> values;
    for (const glm::vec4& v : channel.values) {
      values.insert(values.end(), {v.x, v.y, v.z});
      if (rotation) values.push_back(v.w);
    }
    const int output =
        buffer.addFloats(values, rotation ? 4 : 3, rotation ? "VEC4" : "VEC3", false);
    channels.push_back({{"sampler", samplers.size()},
                        {"target", {{"node", channel.joint}, {"path", pathName(channel.path)}}}});
    samplers.push_back({{"input", input->second},
                        {"interpolation", interpolationName(channel.interpolation)},
                        {"output", output}});
  }
  return {{"name", clip.name}, {"channels", channels}, {"samplers", samplers}};
}

}  // namespace

GltfFiles toGltf(const Character& character, const std::string& binUri,
                 const std::string& imageUri) {
  Json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "demo_engine tools/assetgen"}};
  doc["scene"] = 0;
  const int meshNode = static_cast<int>(character.joints.size());
  doc["scenes"] = Json::array({{{"name", character.name}, {"nodes", {meshNode, 0}}}});
  doc["nodes"] = nodesJson(character);
  // Keys that the builders below fill, created now so the file reads top-down.
  for (const char* key : {"meshes", "materials", "textures", "samplers", "images", "skins",
                          "animations", "accessors", "bufferViews", "buffers"}) {
    doc[key] = Json::array();
  }
  BufferBuilder buffer(doc);
  doc["meshes"].push_back(
      {{"name", character.name}, {"primitives", Json::array({primitiveJson(character, buffer)})}});
  doc["materials"].push_back({{"name", character.name + "_paint"},
                              {"pbrMetallicRoughness",
                               {{"baseColorTexture", {{"index", 0}}},
                                {"metallicFactor", 0.0f},
                                {"roughnessFactor", 0.6f}}}});
  doc["textures"].push_back({{"sampler", 0}, {"source", 0}});
  doc["samplers"].push_back({{"magFilter", kLinear},
                             {"minFilter", kLinearMipmapLinear},
                             {"wrapS", kClampToEdge},
                             {"wrapT", kClampToEdge}});
  doc["images"].push_back({{"name", character.name + "_albedo"}, {"uri", imageUri}});
  doc["skins"].push_back(skinJson(character, buffer));
  for (const Clip& clip : character.clips) doc["animations"].push_back(animationJson(clip, buffer));
  GltfFiles files;
  files.bin = buffer.take();
  doc["buffers"].push_back({{"uri", binUri}, {"byteLength", files.bin.size()}});
  files.json = doc.dump(1) + "\n";
  return files;
}

}  // namespace assetgen
