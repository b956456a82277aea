#include "caustica/util/atomic_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "caustica/util/error.h"

namespace caustica {

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
    const std::string tmp = path + ".tmp";
    try {
        {
            std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
            if (!f) throw Error(path + ": cannot write (the folder is missing or not writable)");
            try {
                write(f);
            } catch (const Error& e) {
                throw Error(path + ": " + e.what());
            }
            f.flush();
            if (!f) throw Error(path + ": writing failed (disk full?)");
        }
        std::error_code ec;
        std::filesystem::rename(tmp, path, ec);
        if (ec) throw Error(path + ": cannot replace it (" + ec.message() + ")");
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        throw;
    }
}

}  // namespace caustica
