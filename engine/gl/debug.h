#pragma once
// GL debug output (KHR_debug, core in 4.3). When on, every driver message goes to
// the log and every error-type message is counted, so a test can fail on any GL
// error instead of sampling glGetError at a few places.
namespace engine::gl {

void enableDebugOutput();
// Error-type messages seen since the last reset, plus any pending glGetError codes.
int errorCount();
void resetErrorCount();

}  // namespace engine::gl
