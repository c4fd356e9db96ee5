#pragma once
// Linear RGB in float files: OpenEXR (through tinyexr) and PFM. The programs write
// them for --screenshot F.exr / F.pfm (a renderer's radiance before exposure, tone
// map and output curve) and imgdiff reads them beside Radiance .hdr
// (core/linear_image.h). Writing picks the format by the file's name; reading tells
// the two apart by their content, as core/linear_image.h does.
#include <optional>
#include <string>

#include "core/linear_image.h"
#include "core/result.h"

namespace engine {

enum class FloatFormat { Exr, Pfm };

// A file name's extension in lower case, with its dot (".exr"); "" when none.
std::string lowerCaseExtension(const std::string& path);
// The format a file's name asks for: ".exr" or ".pfm", in any case; none otherwise.
std::optional<FloatFormat> floatFormatForName(const std::string& path);
// The format of the file's first bytes (OpenEXR's magic number, PFM's "PF"); none
// when neither, or when it cannot be read.
std::optional<FloatFormat> floatFormatOfFile(const std::string& path);
// Whether `path` is to be read or written as a float image: by its content, or by
// its name when the content says nothing (a missing or broken file then gets the
// float reader's error rather than another format's).
bool isFloatImageFile(const std::string& path);

// The image in the format the name asks for, written to a temporary beside `path`
// and renamed, so that a failure leaves nothing half-written. Errors name the file.
Status writeFloatImage(const std::string& path, const FloatImage& image);

// A scanline OpenEXR file's R, G and B channels (half or float; other channels are
// ignored) or a colour PFM ("PF", either byte order). Errors name the file: no such
// file, neither format, a truncated or malformed file, a size over the limits of
// core/linear_image.h, a wrong number of bytes.
Result<FloatImage> readFloatImage(const std::string& path);

}  // namespace engine
