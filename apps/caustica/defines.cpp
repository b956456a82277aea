#include <map>
#include <string>
#include <vector>

#include "commands.h"
#include "caustica/util/error.h"

namespace caustica::cli {

std::map<std::string, std::string> parseDefines(const std::vector<std::string>& defines) {
    std::map<std::string, std::string> out;
    for (const std::string& d : defines) {
        size_t eq = d.find('=');
        if (eq == std::string::npos || eq == 0)
            throw Error("-D " + d + ": expected name=value");
        out[d.substr(0, eq)] = d.substr(eq + 1);
    }
    return out;
}

}  // namespace caustica::cli
