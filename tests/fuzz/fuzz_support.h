#pragma once
// Helpers shared by the fuzz targets.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/log.h"

namespace fuzz {

// Loaders that only take a path get the input through this file: one per process
// so that parallel fuzzers (-jobs) do not overwrite each other's input, removed
// at exit so that runs leave nothing in /tmp.
class TempFile {
 public:
  explicit TempFile(const char* suffix)
      : path_("/tmp/engine_fuzz_" + std::to_string(::getpid()) + suffix) {}
  ~TempFile() { std::remove(path_.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& write(const std::uint8_t* data, std::size_t size) const {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (f == nullptr) std::abort();
    if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
    return path_;
  }

 private:
  std::string path_;
};

// Warnings go to stderr; at thousands of inputs a second they would drown the
// fuzzer's own output and slow it down.
inline void quietLogs() { engine::setLogLevel(engine::LogLevel::Error); }

}  // namespace fuzz
