// Image bytes -> engine::decodePng (readPng's decoder; stb_image underneath) and,
// for the same bytes written to a file, readPng itself, which must agree.
#include <cstdint>
#include <cstdlib>
#include <span>

#include "core/image.h"
#include "fuzz_support.h"

namespace {
fuzz::TempFile* file = nullptr;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  static fuzz::TempFile png(".png");
  file = &png;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto image = engine::decodePng(std::span(data, size), "fuzz.png");
  if (image) {
    if (image->width < 1 || image->height < 1 || image->width > engine::kMaxImageSide ||
        image->height > engine::kMaxImageSide ||
        image->pixels.size() != static_cast<std::size_t>(image->width) * image->height * 4)
      std::abort();
  } else if (image.error().message.rfind("fuzz.png: ", 0) != 0) {
    std::abort();
  }
  // The file path must give the same answer as the memory path.
  auto fromFile = engine::readPng(file->write(data, size));
  if (fromFile.ok() != image.ok()) std::abort();
  if (fromFile && fromFile->pixels != image->pixels) std::abort();
  return 0;
}
