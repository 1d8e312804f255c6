#pragma once
// Decoding an encoded image (PNG, JPEG, OpenEXR, ...) held in memory — a .glb's buffer view, a data
// URI, or an external file's bytes — through OpenImageIO, not stb (DEPENDENCIES.md pitfall 3).
// A stand-in until the textures module offers decoding from memory (issue 4); then this goes.
#include <string>
#include <vector>

#include "textures/image.h"

namespace svbrdf {

// Values as stored (no color conversion), as floats. `format_hint` is a mime type or a file name
// whose extension names the format; the bytes' signature wins when it disagrees. Throws
// svbrdf::Error "where: ..." when the bytes do not decode.
Image decode_image(const std::vector<unsigned char>& bytes, const std::string& format_hint, const std::string& where);

}  // namespace svbrdf
