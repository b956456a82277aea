// oidn_denoiser.h — Intel Open Image Denoise, loaded at run time (dlopen): caustica neither
// links nor needs it. The library is looked for in this order:
//   1. the path the caller gives (`--oidn-library PATH`): it must load, else caustica::Error;
//   2. the environment variable CAUSTICA_OIDN_LIBRARY (same rule);
//   3. a pyoidn wheel (it bundles libOpenImageDenoise 2.x) in the site-packages of every
//      python3 on PATH, of $VIRTUAL_ENV, ~/.local and /usr/lib/python3/dist-packages;
//   4. the system's library path (libOpenImageDenoise.so.2, libOpenImageDenoise.so).
// Only OIDN's C API 2.x functions declared in oidn_denoiser.cpp are used.
#pragma once

#include <string>

#include "caustica/film/denoise_features.h"
#include "caustica/film/image.h"

namespace caustica {

/// The one line shown when no OIDN library is found.
inline constexpr const char* kOidnNotFound =
    "OIDN not found: give --oidn-library or install pyoidn (pip install pyoidn)";

/// Where the OIDN library would be loaded from (steps 1-4 above): a file path, or a bare soname
/// for step 4, or "" when none is found. Throws caustica::Error when `userPath` (or the
/// environment variable) names a file that does not exist.
std::string findOidnLibrary(const std::string& userPath = "");

struct OidnOptions {
    std::string library;  ///< user-given library path ("" to search)
    int threads = 0;      ///< OIDN's numThreads (0: its own choice)
};

/// Denoises `color` (linear HDR) with OIDN's "RT" filter on its CPU device, with the albedo and
/// the normal guides when given (OIDN takes a normal only together with an albedo; depth and
/// variance are not OIDN inputs and are ignored). Non-finite input values are passed as 0.
/// Throws caustica::Error: kOidnNotFound, a library that does not load or lacks a function, or
/// the error OIDN reports.
Image denoiseOidn(const Image& color, const DenoiseFeatures& features, const OidnOptions& options);

}  // namespace caustica
