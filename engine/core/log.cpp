#include "core/log.h"

#include <cstdio>

namespace engine {
namespace {
LogLevel gLevel = LogLevel::Info;

const char* prefix(LogLevel level) {
  switch (level) {
    case LogLevel::Debug: return "debug: ";
    case LogLevel::Info: return "";
    case LogLevel::Warning: return "warning: ";
    case LogLevel::Error: return "error: ";
  }
  return "";
}
}  // namespace

void setLogLevel(LogLevel level) { gLevel = level; }

void log(LogLevel level, std::string_view message) {
  if (level < gLevel) return;
  std::fprintf(stderr, "%s%.*s\n", prefix(level), static_cast<int>(message.size()), message.data());
}

}  // namespace engine
