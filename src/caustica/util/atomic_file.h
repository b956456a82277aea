// atomic_file.h — writing a file so that a kill at any moment leaves either the old file or the
// new one, never a torn one: the bytes go to PATH.tmp, which is then renamed over PATH.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

namespace caustica {

/// Writes `path` through `write` into `path`.tmp, then renames it over `path`. Errors
/// (caustica::Error) name `path`, never the temporary file; the temporary file is removed.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace caustica
