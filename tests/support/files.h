#pragma once
// Small file helpers the test files share (one definition: the test binaries are
// compiled in unity batches, where two files' copies would collide).
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

namespace engine::test {

// The whole file; empty when it cannot be read (the caller's expectations then fail).
inline std::vector<unsigned char> readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

}  // namespace engine::test
