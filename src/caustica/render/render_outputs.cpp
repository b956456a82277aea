#include "caustica/render/render_outputs.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "caustica/film/tonemap.h"
#include "caustica/io/exr_layers.h"
#include "caustica/io/image_io.h"
#include "caustica/render/renderer.h"
#include "caustica/util/atomic_file.h"
#include "caustica/util/error.h"
#include "caustica/util/progress.h"

namespace caustica {

namespace fs = std::filesystem;

void checkWritablePath(const std::string& path, const char* what) {
    const fs::path p(path);
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw Error(path + ": cannot write the " + what + ": folder " + dir.string() + " does not exist");
    if (fs::is_directory(p, ec)) throw Error(path + ": cannot write the " + what + ": it is a folder");
    // A real write, not access(): root passes every permission check, but not a read-only disk.
    if (fs::exists(p, ec)) {
        if (::access(p.c_str(), W_OK) != 0 || !std::ofstream(path, std::ios::binary | std::ios::app))
            throw Error(path + ": cannot write the " + what + ": permission denied");
        return;
    }
    const std::string probe = path + ".tmp";
    const bool writable = static_cast<bool>(std::ofstream(probe, std::ios::binary));
    fs::remove(probe, ec);
    if (!writable) throw Error(path + ": cannot write the " + what + " in folder " + dir.string());
}

void checkImageOutputPath(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    if (ext != ".exr" && ext != ".pfm" && ext != ".png")
        throw Error(path + ": unknown image format '" + ext + "' (use .exr, .pfm or .png)");
    checkWritablePath(path, "image");
}

std::string defaultOutputPath(const std::string& scenePath, const FilmDesc& film) {
    return fs::path(scenePath).stem().string() + (film.tonemap.ldr ? ".png" : ".exr");
}

void writeImageThroughTemporary(const std::string& path, const std::function<void(const std::string&)>& write) {
    const std::string tmp = path + ".tmp" + fs::path(path).extension().string();
    try {
        write(tmp);
    } catch (const Error& e) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw Error(path + ": cannot write the image (" + e.what() + ")");
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw Error(path + ": cannot write the image (" + ec.message() + ")");
}

ImageMetadata renderImageMetadata(const Renderer& r) {
    // Whole-render figures, the same on every rank: no collective (rank 0 alone writes images).
    const RenderProgress progress = r.progress();
    ImageMetadata meta;
    std::ostringstream spp;
    spp << progress.samplesPerPixel;
    meta.entries["caustica.spp"] = spp.str();
    meta.entries["caustica.renderTime"] = std::to_string(progress.seconds);
    meta.entries["caustica.integrator"] = r.integrator();
    meta.entries["caustica.accel"] = r.accelName();
    meta.entries["caustica.seed"] = std::to_string(r.seed());
    meta.entries["caustica.scene"] = r.scene().sourceFile;
    meta.entries["caustica.invalidSamples"] = std::to_string(r.session().counters().invalidSamples);
    return meta;
}

void writeRenderImages(const std::vector<std::string>& paths, const Image& image, const Renderer& r,
                       const StereoOutputs& stereo) {
    if (stereo.enabled != (r.scene().film.eyeWidth > 0))
        throw Error("the stereo outputs do not match the render (stereo " + std::string(stereo.enabled ? "outputs" : "render") +
                    " without a stereo " + (stereo.enabled ? "render" : "outputs") + ")");
    const ImageMetadata meta = renderImageMetadata(r);
    const ToneMapDesc& tonemap = r.scene().film.tonemap;
    Image ldr;  // tone-mapped once, for every PNG output of an ldrfilm
    AovImage aovs;  // developed once, for every EXR output of a render with AOVs
    for (const std::string& p : paths) {
        // Written beside the target and renamed, so a killed render never leaves a torn image.
        const std::string ext = fs::path(p).extension().string();
        if (stereo.enabled && (ext == ".exr" || ext == ".EXR")) {
            if (r.hasAovs() && aovs.empty()) aovs = r.developAovs();
            writeStereoExr(p, image, meta, stereo.separate, aovs);
            continue;
        }
        const bool toneMapped = tonemap.ldr && (ext == ".png" || ext == ".PNG");
        if (toneMapped && ldr.empty()) ldr = displayToPngLinear(toneMap(image, tonemap));
        writeImageThroughTemporary(p, [&](const std::string& tmp) {
            // EXR: the AOVs as layers of the same file (io/exr_layers.h); PNG, PFM: the image only.
            if (r.hasAovs() && (ext == ".exr" || ext == ".EXR")) {
                if (aovs.empty()) aovs = r.developAovs();
                writeExrLayers(tmp, image, aovs, meta);
            } else {
                writeImage(tmp, toneMapped ? ldr : image, meta);
            }
        });
    }
    if (stereo.enabled && !stereo.anaglyph.empty()) {
        if (tonemap.ldr && ldr.empty()) ldr = displayToPngLinear(toneMap(image, tonemap));
        writeAnaglyphPng(stereo.anaglyph, tonemap.ldr ? ldr : image, meta);
    }
}

void printRenderSummary(const Renderer& r, std::FILE* out) {
    const RenderStats s = r.stats();  // collective over ranks: every rank calls, out == nullptr prints nothing
    if (!out) return;
    const double run = r.runSeconds();
    std::fprintf(out, "time        %s (%.3f s)", ProgressReporter::formatDuration(s.seconds).c_str(), s.seconds);
    if (std::abs(run - s.seconds) > 1e-9) std::fprintf(out, ", of which this run %.3f s", run);
    std::fprintf(out, "\nspp         %d\n", s.samplesPerPixel);
    std::fprintf(out, "samples/s   %.4g M\n", run > 0 ? double(s.samples) / run * 1e-6 : 0.0);
    std::fprintf(out, "rays/s      %.4g M (%llu rays)\n", run > 0 ? double(s.rays) / run * 1e-6 : 0.0,
                 (unsigned long long)s.rays);
    std::fprintf(out, "invalid     %llu samples (NaN/Inf/negative, dropped)\n", (unsigned long long)s.invalidSamples);
    r.session().printSummary(out);
}

namespace {
std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
            continue;
        }
        out += c;
    }
    return out + "\"";
}
}  // namespace

void writeRenderStatsJson(const std::string& path, const Renderer& r, bool cancelled) {
    const RenderStats s = r.stats();
    const double run = r.runSeconds();
    const int ranks = r.comm().size();
    const std::vector<RankStats> perRank = ranks > 1 ? r.rankStats() : std::vector<RankStats>{};
    const uint64_t collectives = r.comm().collectives();  // rank 0's meetings, these two included
    if (!r.comm().isRoot()) return;  // collective over ranks: rank 0 writes
    writeFileAtomically(path, [&](std::ostream& f) {
        f << "{\n"
          << "  \"scene\": " << jsonString(r.scene().sourceFile) << ",\n"
          << "  \"integrator\": \"" << r.integrator() << "\",\n"
          << "  \"device\": \"" << deviceName(r.device().kind) << "\",\n"
          << "  \"accel\": \"" << r.accelName() << "\",\n"
          << "  \"accel_description\": " << jsonString(r.accelDescription()) << ",\n"
          << "  \"seed\": " << r.seed() << ",\n"
          << "  \"seconds\": " << s.seconds << ",\n"
          << "  \"run_seconds\": " << run << ",\n"
          << "  \"accel_build_seconds\": " << r.accelBuildSeconds() << ",\n"
          << "  \"spp\": " << s.samplesPerPixel << ",\n"
          << "  \"samples\": " << s.samples << ",\n"
          << "  \"rays\": " << s.rays << ",\n"
          << "  \"samples_per_second\": " << (run > 0 ? double(s.samples) / run : 0) << ",\n"
          << "  \"rays_per_second\": " << (run > 0 ? double(s.rays) / run : 0) << ",\n"
          << "  \"invalid_samples\": " << s.invalidSamples << ",\n"
          << "  \"cancelled\": " << (cancelled ? "true" : "false");
        if (ranks > 1) {  // the totals above are summed over the ranks; each rank's share:
            f << ",\n  \"ranks\": " << ranks << ",\n  \"collectives\": " << collectives << ",\n  \"per_rank\": [";
            for (size_t i = 0; i < perRank.size(); ++i)
                f << (i ? ", " : "") << "{\"rank\": " << i << ", \"samples\": " << perRank[i].samples
                  << ", \"rays\": " << perRank[i].rays << ", \"seconds\": " << perRank[i].seconds << "}";
            f << "]";
        }
        for (const auto& [key, value] : r.session().statsJson()) f << ",\n  \"" << key << "\": " << value;
        f << "\n}\n";
    });
}

}  // namespace caustica
