// oidn_denoiser.cpp — finding, loading and calling Open Image Denoise 2.x through its C API.
#include "caustica/film/oidn_denoiser.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <mutex>
#include <sstream>
#include <vector>

#include "caustica/util/error.h"

namespace caustica {

namespace {

namespace fs = std::filesystem;

// ---- the part of OIDN's C API (include/OpenImageDenoise/oidn.h, 2.x) caustica calls ------------
using OIDNDevice = struct OIDNDeviceImpl*;
using OIDNFilter = struct OIDNFilterImpl*;
using OIDNBuffer = struct OIDNBufferImpl*;
constexpr int kOidnDeviceTypeCpu = 1;  // OIDN_DEVICE_TYPE_CPU
constexpr int kOidnErrorNone = 0;      // OIDN_ERROR_NONE
constexpr int kOidnFormatFloat3 = 3;   // OIDN_FORMAT_FLOAT3

struct OidnApi {
    OIDNDevice (*newDevice)(int type);                                  // oidnNewDevice
    void (*setDeviceInt)(OIDNDevice, const char* name, int value);      // oidnSetDeviceInt / 1i
    void (*commitDevice)(OIDNDevice);                                   // oidnCommitDevice
    int (*getDeviceError)(OIDNDevice, const char** outMessage);         // oidnGetDeviceError
    void (*releaseDevice)(OIDNDevice);                                  // oidnReleaseDevice
    OIDNBuffer (*newBuffer)(OIDNDevice, size_t byteSize);               // oidnNewBuffer
    void (*writeBuffer)(OIDNBuffer, size_t offset, size_t size, const void* src);  // oidnWriteBuffer
    void (*readBuffer)(OIDNBuffer, size_t offset, size_t size, void* dst);         // oidnReadBuffer
    void (*releaseBuffer)(OIDNBuffer);                                  // oidnReleaseBuffer
    OIDNFilter (*newFilter)(OIDNDevice, const char* type);              // oidnNewFilter
    void (*setFilterImage)(OIDNFilter, const char* name, OIDNBuffer, int format, size_t width,
                           size_t height, size_t byteOffset, size_t pixelStride,
                           size_t rowStride);                           // oidnSetFilterImage
    void (*setFilterBool)(OIDNFilter, const char* name, bool value);    // oidnSetFilterBool / 1b
    void (*commitFilter)(OIDNFilter);                                   // oidnCommitFilter
    void (*executeFilter)(OIDNFilter);                                  // oidnExecuteFilter
    void (*releaseFilter)(OIDNFilter);                                  // oidnReleaseFilter
};

/// dlsym of the first of `names` that exists (OIDN 2.2 renamed oidnSetFilter1b to
/// oidnSetFilterBool and keeps the old name only as an inline wrapper).
template <class Fn>
void bind(void* handle, const std::string& path, Fn& fn, std::initializer_list<const char*> names) {
    for (const char* name : names)
        if (void* sym = dlsym(handle, name)) {
            fn = reinterpret_cast<Fn>(sym);
            return;
        }
    throw Error(path, 0, std::string("not an Open Image Denoise 2.x library: it lacks ") + *names.begin());
}

OidnApi loadApi(const std::string& path) {
    // Loaded once per path for the life of the process (OIDN keeps worker threads).
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = dlerror();
        throw Error(path, 0, std::string("cannot load the OIDN library: ") + (why ? why : "unknown reason"));
    }
    OidnApi api{};
    bind(handle, path, api.newDevice, {"oidnNewDevice"});
    bind(handle, path, api.setDeviceInt, {"oidnSetDeviceInt", "oidnSetDevice1i"});
    bind(handle, path, api.commitDevice, {"oidnCommitDevice"});
    bind(handle, path, api.getDeviceError, {"oidnGetDeviceError"});
    bind(handle, path, api.releaseDevice, {"oidnReleaseDevice"});
    bind(handle, path, api.newBuffer, {"oidnNewBuffer"});
    bind(handle, path, api.writeBuffer, {"oidnWriteBuffer"});
    bind(handle, path, api.readBuffer, {"oidnReadBuffer"});
    bind(handle, path, api.releaseBuffer, {"oidnReleaseBuffer"});
    bind(handle, path, api.newFilter, {"oidnNewFilter"});
    bind(handle, path, api.setFilterImage, {"oidnSetFilterImage"});
    bind(handle, path, api.setFilterBool, {"oidnSetFilterBool", "oidnSetFilter1b"});
    bind(handle, path, api.commitFilter, {"oidnCommitFilter"});
    bind(handle, path, api.executeFilter, {"oidnExecuteFilter"});
    bind(handle, path, api.releaseFilter, {"oidnReleaseFilter"});
    return api;
}

// ---- search -------------------------------------------------------------------------------------

/// The OIDN main library inside a pyoidn install (its file name starts "libOpenImageDenoise.so";
/// the _core and _device_* libraries beside it are loaded by that one).
std::string findInPyoidn(const fs::path& sitePackages) {
    std::error_code ec;
    const fs::path dir = sitePackages / "pyoidn";
    if (!fs::is_directory(dir, ec)) return "";
    std::vector<std::string> found;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        if (it.depth() > 3) it.disable_recursion_pending();
        const std::string name = it->path().filename().string();
        if (name.rfind("libOpenImageDenoise.so", 0) == 0 && it->is_regular_file(ec)) found.push_back(it->path());
    }
    if (found.empty()) return "";
    std::sort(found.begin(), found.end());  // deterministic choice among libX.so, libX.so.2, ...
    return found.front();
}

/// site-packages folders to look in: every python3 on PATH (<prefix>/bin/python3 ->
/// <prefix>/lib/python3.*/site-packages), $VIRTUAL_ENV, ~/.local, Debian's dist-packages.
std::vector<fs::path> sitePackagesCandidates() {
    std::vector<fs::path> prefixes;
    if (const char* venv = std::getenv("VIRTUAL_ENV")) prefixes.emplace_back(venv);
    if (const char* path = std::getenv("PATH")) {
        std::stringstream ss(path);
        std::string dir;
        std::error_code ec;
        while (std::getline(ss, dir, ':'))
            if (!dir.empty() && fs::exists(fs::path(dir) / "python3", ec)) prefixes.push_back(fs::path(dir).parent_path());
    }
    if (const char* home = std::getenv("HOME")) prefixes.push_back(fs::path(home) / ".local");
    std::vector<fs::path> out;
    std::error_code ec;
    for (const fs::path& prefix : prefixes) {
        const fs::path lib = prefix / "lib";
        if (!fs::is_directory(lib, ec)) continue;
        std::vector<fs::path> versions;
        for (const auto& entry : fs::directory_iterator(lib, ec))
            if (entry.path().filename().string().rfind("python3", 0) == 0) versions.push_back(entry.path() / "site-packages");
        std::sort(versions.begin(), versions.end());
        out.insert(out.end(), versions.begin(), versions.end());
    }
    out.emplace_back("/usr/lib/python3/dist-packages");
    return out;
}

std::string checkedUserPath(const std::string& path, const char* origin) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw Error(path, 0, std::string("OIDN library (") + origin + ") does not exist or is not a file");
    return path;
}

/// Frees an OIDN object at scope exit.
template <class T>
struct OidnHandle {
    T handle;
    void (*release)(T);
    ~OidnHandle() {
        if (handle) release(handle);
    }
};

}  // namespace

std::string findOidnLibrary(const std::string& userPath) {
    if (!userPath.empty()) return checkedUserPath(userPath, "--oidn-library");
    if (const char* env = std::getenv("CAUSTICA_OIDN_LIBRARY"); env && *env)
        return checkedUserPath(env, "CAUSTICA_OIDN_LIBRARY");
    for (const fs::path& site : sitePackagesCandidates())
        if (std::string lib = findInPyoidn(site); !lib.empty()) return lib;
    for (const char* soname : {"libOpenImageDenoise.so.2", "libOpenImageDenoise.so"})
        if (void* handle = dlopen(soname, RTLD_LAZY | RTLD_LOCAL | RTLD_NOLOAD)) {
            dlclose(handle);
            return soname;
        } else if ((handle = dlopen(soname, RTLD_LAZY | RTLD_LOCAL))) {
            dlclose(handle);
            return soname;
        }
    return "";
}

Image denoiseOidn(const Image& color, const DenoiseFeatures& features, const OidnOptions& options) {
    const std::string path = findOidnLibrary(options.library);
    if (path.empty()) throw Error(kOidnNotFound);
    for (const auto* guide : {&features.albedo, &features.normal})
        if (*guide && !(*guide)->sameSize(color)) throw Error("denoise: a guide image differs in size from the colour");
    if (features.normal && !features.albedo)
        throw Error("denoise: OIDN uses a normal image only together with an albedo image (give --albedo too)");
    const OidnApi api = loadApi(path);

    OidnHandle<OIDNDevice> device{api.newDevice(kOidnDeviceTypeCpu), api.releaseDevice};
    auto check = [&](const char* step) {
        const char* message = nullptr;
        if (api.getDeviceError(device.handle, &message) != kOidnErrorNone)
            throw Error(std::string("OIDN ") + step + ": " + (message ? message : "unknown error"));
    };
    if (!device.handle) {
        const char* message = nullptr;
        api.getDeviceError(nullptr, &message);
        throw Error(std::string("OIDN: cannot create a CPU device: ") + (message ? message : "unknown error"));
    }
    if (options.threads > 0) api.setDeviceInt(device.handle, "numThreads", options.threads);
    api.commitDevice(device.handle);
    check("device");

    const size_t bytes = color.rgb.size() * sizeof(float);
    auto upload = [&](const Image& image) {
        std::vector<float> v(image.rgb);
        for (float& x : v) x = std::isfinite(x) ? x : 0.0f;
        OIDNBuffer buffer = api.newBuffer(device.handle, bytes);
        check("buffer");
        api.writeBuffer(buffer, 0, bytes, v.data());
        return buffer;
    };
    OidnHandle<OIDNBuffer> colorBuf{upload(color), api.releaseBuffer};
    OidnHandle<OIDNBuffer> albedoBuf{features.albedo ? upload(*features.albedo) : nullptr, api.releaseBuffer};
    OidnHandle<OIDNBuffer> normalBuf{features.normal ? upload(*features.normal) : nullptr, api.releaseBuffer};
    OidnHandle<OIDNBuffer> outBuf{api.newBuffer(device.handle, bytes), api.releaseBuffer};
    check("buffer");

    OidnHandle<OIDNFilter> filter{api.newFilter(device.handle, "RT"), api.releaseFilter};
    check("filter");
    const size_t w = size_t(color.width), h = size_t(color.height);
    api.setFilterImage(filter.handle, "color", colorBuf.handle, kOidnFormatFloat3, w, h, 0, 0, 0);
    if (albedoBuf.handle)
        api.setFilterImage(filter.handle, "albedo", albedoBuf.handle, kOidnFormatFloat3, w, h, 0, 0, 0);
    if (normalBuf.handle)
        api.setFilterImage(filter.handle, "normal", normalBuf.handle, kOidnFormatFloat3, w, h, 0, 0, 0);
    api.setFilterImage(filter.handle, "output", outBuf.handle, kOidnFormatFloat3, w, h, 0, 0, 0);
    api.setFilterBool(filter.handle, "hdr", true);
    api.commitFilter(filter.handle);
    check("filter setup");
    api.executeFilter(filter.handle);
    check("denoising");

    Image result(color.width, color.height);
    api.readBuffer(outBuf.handle, 0, bytes, result.rgb.data());
    check("read-back");
    return result;
}

}  // namespace caustica
