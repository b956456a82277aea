#include "py_options.h"

#include <cmath>

#include "caustica/util/error.h"

namespace caustica::py {

namespace pyb = pybind11;

namespace {

bool isNone(const pyb::object& o) { return !o || o.is_none(); }

std::string reprText(const pyb::handle& value) { return pyb::str(pyb::repr(value)).cast<std::string>(); }

/// An int in [lo, hi] (bool refused: True is not a sample count).
int64_t integerIn(const pyb::object& value, const std::string& keyword, int64_t lo, int64_t hi) {
    if (!pyb::isinstance<pyb::int_>(value) || pyb::isinstance<pyb::bool_>(value))
        throw Error(keyword + "=" + reprText(value) + ": expected an integer");
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0 || v < lo || v > hi)
        throw Error(keyword + "=" + reprText(value) + ": expected an integer in [" + std::to_string(lo) + ", " +
                    std::to_string(hi) + "]");
    return v;
}

double finiteIn(const pyb::object& value, const std::string& keyword, double lo, double hi, const char* bounds) {
    if (!(pyb::isinstance<pyb::int_>(value) || pyb::isinstance<pyb::float_>(value)) || pyb::isinstance<pyb::bool_>(value))
        throw Error(keyword + "=" + reprText(value) + ": expected a number");
    const double v = value.cast<double>();
    if (!std::isfinite(v) || v < lo || v > hi) throw Error(keyword + "=" + reprText(value) + ": expected a finite number in " + bounds);
    return v;
}

std::string text(const pyb::object& value, const std::string& keyword) {
    if (!pyb::isinstance<pyb::str>(value)) throw Error(keyword + "=" + reprText(value) + ": expected a string");
    return value.cast<std::string>();
}

StereoSettings stereoSettings(const pyb::object& value) {
    StereoSettings s;
    if (pyb::isinstance<pyb::str>(value)) {
        s.mode = parseStereoMode(value.cast<std::string>());
    } else if (pyb::isinstance<pyb::dict>(value)) {
        bool hasMode = false;
        for (const auto& [key, v] : value.cast<pyb::dict>()) {
            const std::string k = pyb::str(key).cast<std::string>();
            const pyb::object item = pyb::reinterpret_borrow<pyb::object>(v);
            if (k == "mode") {
                s.mode = parseStereoMode(text(item, "stereo['mode']"));
                hasMode = true;
            } else if (k == "interocular" || k == "convergence") {
                const Float d = Float(finiteIn(item, "stereo['" + k + "']", 0, 1e30, "(0, inf)"));
                (k == "interocular" ? s.interocular : s.convergence) = d;
            } else {
                throw Error("stereo: unknown key '" + k + "' (use mode, interocular, convergence)");
            }
        }
        if (!hasMode) throw Error("stereo: the dict needs a 'mode' (off-axis, parallel or toe-in)");
    } else {
        throw Error("stereo=" + reprText(value) + ": expected a mode ('off-axis', 'parallel', 'toe-in') or a dict");
    }
    checkStereoSettings(s);
    return s;
}

std::string aovList(const pyb::object& value) {
    std::string list;
    if (pyb::isinstance<pyb::str>(value)) return value.cast<std::string>();
    if (!(pyb::isinstance<pyb::list>(value) || pyb::isinstance<pyb::tuple>(value)))
        throw Error("aovs=" + reprText(value) + ": expected 'NAME:TYPE,...' or a list of 'NAME:TYPE'");
    for (const pyb::handle item : value) list += (list.empty() ? "" : ",") + text(pyb::reinterpret_borrow<pyb::object>(item), "aovs");
    if (list.empty()) throw Error("aovs: the list is empty");
    return list;
}

}  // namespace

std::string valueText(const pyb::handle& value, const std::string& keyword) {
    if (pyb::isinstance<pyb::bool_>(value)) return value.cast<bool>() ? "true" : "false";
    if (pyb::isinstance<pyb::str>(value)) return value.cast<std::string>();
    if (pyb::isinstance<pyb::int_>(value) || pyb::isinstance<pyb::float_>(value)) return pyb::str(value).cast<std::string>();
    throw Error(keyword + "=" + reprText(value) + ": expected a number, a bool or a string");
}

std::optional<int> threadCount(const pyb::object& threads) {
    if (isNone(threads)) return std::nullopt;
    return int(integerIn(threads, "threads", 1, 4096));
}

RenderRequest renderRequest(const RenderKeywords& k, const std::map<std::string, std::string>& defines) {
    RenderRequest r;
    r.defines = defines;
    if (!isNone(k.integrator)) {
        r.integrator = text(k.integrator, "integrator");
        if (r.integrator.empty()) throw Error("integrator: empty name");
    }
    if (!isNone(k.spp)) r.samplesPerPixel = int(integerIn(k.spp, "spp", 1, 1 << 24));
    if (!isNone(k.time)) r.timeLimit = finiteIn(k.time, "time", 1e-3, 1e7, "[0.001, 10000000] seconds");
    if (!isNone(k.device)) {
        r.device = text(k.device, "device");
        if (r.device != "cpu" && r.device != "cuda" && r.device != "auto")
            throw Error("device='" + r.device + "': expected 'cpu', 'cuda' or 'auto'");
    }
    if (!isNone(k.seed)) r.seed = uint64_t(integerIn(k.seed, "seed", 0, INT64_MAX));
    if (!isNone(k.resolution)) {
        if (!(pyb::isinstance<pyb::tuple>(k.resolution) || pyb::isinstance<pyb::list>(k.resolution)) ||
            pyb::len(k.resolution) != 2)
            throw Error("resolution=" + reprText(k.resolution) + ": expected (width, height)");
        const pyb::sequence wh = k.resolution.cast<pyb::sequence>();
        const int w = int(integerIn(wh[0], "resolution width", 1, 32768));
        const int h = int(integerIn(wh[1], "resolution height", 1, 32768));
        r.resolution = std::make_pair(w, h);
    }
    if (!isNone(k.aovs)) r.aovs = aovList(k.aovs);
    if (!isNone(k.stereo)) r.stereo = stereoSettings(k.stereo);
    if (!isNone(k.sppPerPass)) r.samplesPerPass = int(integerIn(k.sppPerPass, "spp_per_pass", 1, 4096));
    for (const auto& [key, value] : k.integratorParams) {
        const std::string name = pyb::str(key).cast<std::string>();
        r.integratorParams.push_back({name, IntegratorParam::Kind::Text, valueText(value, name), "keyword " + name});
    }
    return r;
}

}  // namespace caustica::py
