#include "robot_texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/gtc/constants.hpp>

namespace assetgen {

namespace {

using Colour = glm::vec3;  // 0..1, stored as the 8-bit sRGB that glTF base colour is

constexpr Colour kWhite{0.88f, 0.89f, 0.91f};
constexpr Colour kOrange{0.94f, 0.47f, 0.12f};
constexpr Colour kBlue{0.16f, 0.43f, 0.78f};
constexpr Colour kDark{0.22f, 0.23f, 0.26f};
constexpr Colour kNavy{0.24f, 0.27f, 0.37f};
constexpr Colour kVisor{0.08f, 0.09f, 0.13f};
constexpr Colour kGlow{0.31f, 0.90f, 1.0f};

// Samples per texel along each axis: edges of the painted shapes are antialiased.
constexpr int kSupersample = 2;

Colour jointColour(int joint) {
  switch (joint) {
    case kPelvis: return kNavy;
    case kSpine:
    case kNeck:
    case kHandL:
    case kHandR: return kDark;
    case kChest:
    case kUpperArmL:
    case kUpperArmR:
    case kFootL:
    case kFootR: return kOrange;
    case kThighL:
    case kThighR: return kBlue;
    default: return kWhite;  // head, forearms, shins
  }
}

// A point of a cell in the part's own terms: u around (0 back, 0.5 front), v along
// (0 at the first point), and the same in metres so round shapes stay round.
struct Surface {
  float u = 0.0f;
  float v = 0.0f;
  glm::vec2 metres{0.0f};
};

struct PartFrame {
  const BodyPart* part = nullptr;
  std::vector<float> fractions;  // pointFractions(part)
  float circumference = 1.0f;
  float length = 1.0f;
};

PartFrame makeFrame(const BodyPart& part) {
  PartFrame frame{&part, pointFractions(part)};
  glm::vec2 widest{0.0f};
  for (glm::vec2 r : part.radii) widest = glm::max(widest, r);
  frame.circumference = glm::two_pi<float>() * std::sqrt(0.5f * glm::dot(widest, widest));
  frame.length = 0.0f;
  for (size_t i = 1; i < part.points.size(); ++i) {
    frame.length += glm::distance(part.points[i - 1], part.points[i]);
  }
  return frame;
}

float circle(glm::vec2 p, glm::vec2 centre, float radius) {
  return glm::length(p - centre) <= radius ? 1.0f : 0.0f;
}

bool inBox(glm::vec2 p, glm::vec2 centre, glm::vec2 half) {
  const glm::vec2 d = glm::abs(p - centre);
  return d.x <= half.x && d.y <= half.y;
}

// Bands in the colour of the segment's joint, split by dark seams where joints meet,
// with panel lines down both sides.
Colour bands(const PartFrame& frame, const Surface& s) {
  const BodyPart& part = *frame.part;
  size_t segment = 0;
  while (segment + 2 < frame.fractions.size() && s.v >= frame.fractions[segment + 1]) ++segment;
  Colour colour = jointColour(part.joints[segment]);
  for (size_t k = 1; k + 1 < frame.fractions.size(); ++k) {
    if (part.joints[k - 1] == part.joints[k]) continue;
    if (std::abs(s.v - frame.fractions[k]) * frame.length < 0.008f) colour = kDark * 0.8f;
  }
  const float sideLine = std::min(std::abs(s.u - 0.25f), std::abs(s.u - 0.75f));
  if (sideLine * frame.circumference < 0.003f) colour *= 0.7f;
  return colour;
}

Colour paintHead(const PartFrame& frame, const Surface& s) {
  Colour colour = bands(frame, s);
  const glm::vec2 p = s.metres;
  const float front = 0.5f * frame.circumference;
  const glm::vec2 visor{front, 0.60f * frame.length};
  if (inBox(p, visor, {0.085f, 0.035f})) colour = kVisor;
  for (float side : {-1.0f, 1.0f}) {
    if (circle(p, visor + glm::vec2(side * 0.04f, 0.0f), 0.016f) > 0.0f) colour = kGlow;
    // Orange "ears" on both sides of the head.
    if (circle(p, {front + side * 0.25f * frame.circumference, 0.55f * frame.length}, 0.03f) >
        0.0f) {
      colour = kOrange;
    }
  }
  // A mouth grille: three horizontal slats.
  const glm::vec2 mouth{front, 0.30f * frame.length};
  if (inBox(p, mouth, {0.04f, 0.02f}) && std::fmod(p.y - mouth.y + 0.02f, 0.016f) < 0.008f) {
    colour = kDark;
  }
  // An orange stripe over the crown, front to back.
  if (s.v > 0.80f && (std::abs(p.x - front) < 0.015f || std::abs(p.x) < 0.015f ||
                      std::abs(p.x - frame.circumference) < 0.015f)) {
    colour = kOrange;
  }
  return colour;
}

Colour paintTorso(const PartFrame& frame, const Surface& s) {
  Colour colour = bands(frame, s);
  const glm::vec2 p = s.metres;
  const float front = 0.5f * frame.circumference;
  const float chestTop = frame.fractions[3] * frame.length;
  const float chestBottom = frame.fractions[2] * frame.length;
  // A white chest plate carrying a blue emblem with an orange core.
  const glm::vec2 plate{front, 0.5f * (chestTop + chestBottom)};
  if (inBox(p, plate, {0.12f, 0.5f * (chestTop - chestBottom) - 0.02f})) {
    colour = kWhite;
    const float r = glm::length(p - plate);
    if (r < 0.05f) colour = kBlue;
    if (r < 0.025f) colour = kOrange;
  }
  // Belly ribs on the spine band.
  if (s.v > frame.fractions[1] && s.v < frame.fractions[2] &&
      std::fmod(p.y - frame.fractions[1] * frame.length, 0.03f) < 0.008f) {
    colour *= 0.6f;
  }
  return colour;
}

Colour paintLeg(const PartFrame& frame, const Surface& s) {
  Colour colour = bands(frame, s);
  const glm::vec2 knee{0.5f * frame.circumference, frame.fractions[2] * frame.length};
  if (inBox(s.metres, knee, {0.045f, 0.05f})) colour = kOrange;
  return colour;
}

Colour paintArm(const PartFrame& frame, const Surface& s) {
  Colour colour = bands(frame, s);
  // Blue elbow pads at the back of the arm.
  const glm::vec2 elbow{0.0f, frame.fractions[2] * frame.length};
  const glm::vec2 p{std::min(s.metres.x, frame.circumference - s.metres.x), s.metres.y};
  if (circle(p, elbow, 0.035f) > 0.0f) colour = kBlue;
  return colour;
}

Colour paintFoot(const PartFrame& frame, const Surface& s) {
  Colour colour = bands(frame, s);
  // The foot's seam runs along the sole: a dark rubber sole and a dark toe cap.
  if (s.u < 0.2f || s.u > 0.8f || s.v > 0.85f) colour = kDark;
  return colour;
}

Colour paintCap(const Surface& s) {
  const float r = glm::length(glm::vec2(s.u, s.v) - 0.5f);
  return r > 0.3f && r < 0.36f ? kOrange : kDark;
}

Colour paintCell(CellId cell, const PartFrame* frame, const Surface& s) {
  switch (cell) {
    case CellId::Head: return paintHead(*frame, s);
    case CellId::Torso: return paintTorso(*frame, s);
    case CellId::Arm: return paintArm(*frame, s);
    case CellId::Leg: return paintLeg(*frame, s);
    case CellId::Neck: return bands(*frame, s);
    case CellId::Foot: return paintFoot(*frame, s);
    case CellId::Cap: return paintCap(s);
    default: return glm::vec3(0.5f);
  }
}

Surface surfaceAt(const AtlasCell& cell, const PartFrame* frame, glm::vec2 atlasUv) {
  Surface s;
  const glm::vec2 local = glm::clamp((atlasUv - cell.min) / (cell.max - cell.min), 0.0f, 1.0f);
  s.u = local.x;
  s.v = local.y;
  if (frame != nullptr) s.metres = {s.u * frame->circumference, s.v * frame->length};
  return s;
}

void paintCellInto(engine::Image& image, CellId cell, const PartFrame* frame) {
  const int cellW = kAtlasSize / kAtlasColumns, cellH = kAtlasSize / kAtlasRows;
  const int index = static_cast<int>(cell);
  const int x0 = (index % kAtlasColumns) * cellW, y0 = (index / kAtlasColumns) * cellH;
  const AtlasCell rect = atlasCell(cell);
  for (int y = y0; y < y0 + cellH; ++y) {
    for (int x = x0; x < x0 + cellW; ++x) {
      Colour sum{0.0f};
      for (int sy = 0; sy < kSupersample; ++sy) {
        for (int sx = 0; sx < kSupersample; ++sx) {
          const glm::vec2 texel{
              static_cast<float>(x) + (static_cast<float>(sx) + 0.5f) / kSupersample,
              static_cast<float>(y) + (static_cast<float>(sy) + 0.5f) / kSupersample};
          sum += paintCell(cell, frame,
                           surfaceAt(rect, frame, texel / static_cast<float>(kAtlasSize)));
        }
      }
      const Colour colour = glm::clamp(sum / float(kSupersample * kSupersample), 0.0f, 1.0f);
      std::uint8_t* px = image.at(x, y);
      for (int c = 0; c < 3; ++c)
        px[c] = static_cast<std::uint8_t>(std::lround(colour[c] * 255.0f));
      px[3] = 255;
    }
  }
}

}  // namespace

engine::Image paintRobotAlbedo(const std::vector<BodyPart>& parts) {
  engine::Image image(kAtlasSize, kAtlasSize);
  for (int c = 0; c < static_cast<int>(CellId::Count); ++c) {
    const auto cell = static_cast<CellId>(c);
    // Mirrored parts share a cell; the first part that uses it sets the bands.
    const auto part =
        std::find_if(parts.begin(), parts.end(), [&](const BodyPart& p) { return p.cell == cell; });
    if (part == parts.end()) {
      paintCellInto(image, cell, nullptr);
      continue;
    }
    const PartFrame frame = makeFrame(*part);
    paintCellInto(image, cell, &frame);
  }
  return image;
}

}  // namespace assetgen
