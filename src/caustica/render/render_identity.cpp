#include "caustica/render/render_identity.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "caustica/util/binary_io.h"
#include "caustica/util/error.h"

namespace caustica {

IdentityEntry identityEntry(std::string name, std::string value) {
    IdentityEntry e{std::move(name), std::move(value), {}};
    e.identity = e.value;
    return e;
}

IdentityEntry fileIdentityEntry(std::string name, const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot read (needed to identify the render for its checkpoint)");
    Fnv1a hash;
    char buffer[1 << 16];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
        hash.add(reinterpret_cast<const unsigned char*>(buffer), size_t(in.gcount()));
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash.h));
    return IdentityEntry{std::move(name), path + ", sha " + hex, hex};
}

namespace {
template <class T, class Parse>
std::string shortestText(T value, Parse parse) {
    char buf[32];
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, double(value));
        if (parse(buf) == value) break;
    }
    return buf;
}
}  // namespace

std::string identityNumber(double value) {
    return shortestText(value, [](const char* s) { return std::strtod(s, nullptr); });
}

std::string identityNumber(float value) {
    return shortestText(value, [](const char* s) { return std::strtof(s, nullptr); });
}

IdentityEntry stereoIdentityEntry(const StereoSettings& s) {
    if (s.mode == StereoMode::Off) return identityEntry("stereo", "off");
    return identityEntry("stereo", std::string(stereoModeName(s.mode)) + ", interocular " + identityNumber(s.interocular) +
                                       ", convergence " + identityNumber(s.convergence));
}

std::string firstIdentityDifference(const RenderIdentity& saved, const RenderIdentity& current) {
    const size_t n = std::max(saved.size(), current.size());
    for (size_t i = 0; i < n; ++i) {
        if (i >= current.size()) return saved[i].name + " differs (" + saved[i].value + " in the checkpoint, not in this render)";
        if (i >= saved.size()) return current[i].name + " differs (not in the checkpoint; now " + current[i].value + ")";
        const IdentityEntry& a = saved[i];
        const IdentityEntry& b = current[i];
        if (a.name != b.name) return b.name + " differs (the checkpoint has " + a.name + " = " + a.value + " instead)";
        if (a.identity != b.identity) return a.name + " differs (written for " + a.value + "; now " + b.value + ")";
    }
    return {};
}

IdentityEntry ranksIdentityEntry(int ranks) { return identityEntry("ranks", std::to_string(ranks)); }

std::string rankCountMismatch(const RenderIdentity& saved, int ranks) {
    std::string written = "1";
    for (const IdentityEntry& e : saved)
        if (e.name == "ranks") written = e.value;
    if (written == std::to_string(ranks)) return "";
    auto count = [](const std::string& n) { return n + (n == "1" ? " process" : " MPI ranks"); };
    return "written by a render over " + count(written) + ", resumed with " + count(std::to_string(ranks)) +
           ": resume it with the same number (" +
           (written == "1" ? std::string("a single process") : "mpirun -n " + written) + ")";
}

}  // namespace caustica
