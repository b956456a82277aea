#include "caustica/distributed/agreed_error.h"

namespace caustica {

std::string failureMessage(const std::exception& e) {
    if (dynamic_cast<const std::bad_alloc*>(&e)) return "out of memory";
    const std::string what = e.what();
    return what.empty() ? "unknown error" : what;
}

}  // namespace caustica
