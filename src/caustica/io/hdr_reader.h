// hdr_reader.h — Radiance RGBE (.hdr) decoding (Greg Ward's format, as Bruce Walter's reader that
// Mitsuba uses): header "#?RADIANCE" or "#?RGBE", FORMAT=32-bit_rle_rgbe, resolution "-Y h +X w",
// scanlines flat or new-style run-length encoded. Written by hand because stb_image's decoder
// loops forever on some truncated files. Every malformed input is a caustica::Error.
#pragma once

#include <string>
#include <vector>

#include "caustica/film/image.h"

namespace caustica {

/// Decodes the bytes of a Radiance file (`path` names it in errors): linear RGB, top row first.
Image decodeRadianceHdr(const std::string& path, const std::vector<unsigned char>& data);

}  // namespace caustica
