#include "core/image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

namespace engine {

void flipVertically(Image& image) {
  const size_t row = static_cast<size_t>(image.width) * 4;
  std::vector<std::uint8_t> tmp(row);
  for (int y = 0; y < image.height / 2; ++y) {
    std::uint8_t* top = image.at(0, y);
    std::uint8_t* bottom = image.at(0, image.height - 1 - y);
    std::copy(top, top + row, tmp.begin());
    std::copy(bottom, bottom + row, top);
    std::copy(tmp.begin(), tmp.end(), bottom);
  }
}

Result<Image> readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!data) {
    return makeError(path + ": cannot read image: " + stbi_failure_reason());
  }
  Image image(w, h);
  std::copy(data, data + static_cast<size_t>(w) * h * 4, image.pixels.begin());
  stbi_image_free(data);
  return image;
}

Status writePng(const std::string& path, const Image& image) {
  if (image.empty()) return makeError(path + ": refusing to write an empty image");
  const std::string tmp = path + ".tmp";
  if (!stbi_write_png(tmp.c_str(), image.width, image.height, 4, image.pixels.data(),
                      image.width * 4)) {
    std::remove(tmp.c_str());
    return makeError(path + ": cannot write PNG (is the folder there and writable?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    return makeError(path + ": cannot write PNG: " + ec.message());
  }
  return Ok{};
}

Result<ImageDiff> compareImages(const Image& a, const Image& b, int threshold) {
  if (a.width != b.width || a.height != b.height) {
    return makeError("images differ in size: " + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                     std::to_string(b.height));
  }
  ImageDiff d;
  d.threshold = threshold;
  double sumAbs = 0.0, sumSq = 0.0;
  size_t over = 0;
  const size_t count = static_cast<size_t>(a.width) * a.height;
  for (size_t i = 0; i < count; ++i) {
    int pixelMax = 0;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c]));
      pixelMax = std::max(pixelMax, diff);
      sumAbs += diff;
      sumSq += double(diff) * diff;
    }
    d.maxAbs = std::max(d.maxAbs, pixelMax);
    if (pixelMax > threshold) ++over;
  }
  const double n = double(count) * 3.0;
  d.meanAbs = count ? sumAbs / n : 0.0;
  d.shareOver = count ? double(over) / double(count) : 0.0;
  const double mse = count ? sumSq / n : 0.0;
  d.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity()
                      : 10.0 * std::log10(255.0 * 255.0 / mse);
  return d;
}

Image diffImage(const Image& a, const Image& b) {
  Image out(std::min(a.width, b.width), std::min(a.height, b.height));
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const int diff = std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
        out.at(x, y)[c] = static_cast<std::uint8_t>(std::min(255, diff * 4));
      }
      out.at(x, y)[3] = 255;
    }
  }
  return out;
}

}  // namespace engine
