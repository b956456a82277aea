// read_file.h — reads a whole input file into memory, refusing directories and unreadable files
// with a caustica::Error naming the file.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "caustica/util/error.h"

namespace caustica::meshio {

/// The file's bytes. `what` names the file's role in messages ("mesh file", "scene file").
inline std::string readWholeFile(const std::string& path, const std::string& what) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error(path, 0, "cannot open " + what + ": it is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, 0, "cannot open " + what);
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw Error(path, 0, "cannot read " + what);
    return ss.str();
}

}  // namespace caustica::meshio
