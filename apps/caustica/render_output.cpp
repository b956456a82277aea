#include "render_output.h"

#include <filesystem>
#include <fstream>

#include "caustica/film/tonemap.h"
#include "caustica/io/image_io.h"
#include "caustica/util/error.h"
#include "caustica/util/progress.h"

namespace caustica::cli {

void checkOutputPath(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (ext != ".exr" && ext != ".pfm" && ext != ".png")
        throw Error(path + ": unknown image format '" + ext + "' (use .exr, .pfm or .png)");
    auto dir = std::filesystem::path(path).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir))
        throw Error(path + ": directory " + dir.string() + " does not exist");
}

std::string defaultOutputPath(const std::string& scenePath, const FilmDesc& film) {
    return std::filesystem::path(scenePath).stem().string() + (film.tonemap.ldr ? ".png" : ".exr");
}

void writeOutputs(const std::vector<std::string>& paths, const Film& film, const RenderStats& stats,
                  const OutputInfo& info) {
    writeImageOutputs(paths, film.develop(), std::to_string(film.samplesPerPixel()), stats, info);
}

void writeImageOutputs(const std::vector<std::string>& paths, const Image& image, const std::string& spp,
                       const RenderStats& stats, const OutputInfo& info) {
    ImageMetadata meta;
    meta.entries["caustica.spp"] = spp;
    meta.entries["caustica.renderTime"] = std::to_string(stats.seconds);
    meta.entries["caustica.integrator"] = info.integrator;
    meta.entries["caustica.accel"] = info.accel;
    meta.entries["caustica.seed"] = std::to_string(info.seed);
    meta.entries["caustica.scene"] = info.scene;
    meta.entries["caustica.invalidSamples"] = std::to_string(stats.invalidSamples);
    Image ldr;  // tone-mapped once, for every PNG output of an ldrfilm
    for (const std::string& p : paths) {
        // Written beside the target and renamed, so a killed render never leaves a torn image.
        const std::string ext = std::filesystem::path(p).extension().string();
        const std::string tmp = p + ".tmp" + ext;
        if (info.tonemap.ldr && (ext == ".png" || ext == ".PNG")) {
            if (ldr.empty()) ldr = displayToPngLinear(toneMap(image, info.tonemap));
            writeImage(tmp, ldr, meta);
            std::filesystem::rename(tmp, p);
            continue;
        }
        writeImage(tmp, image, meta);
        std::filesystem::rename(tmp, p);
    }
}

void printSummary(const RenderStats& s, std::FILE* out) {
    double samplesPerSecond = s.seconds > 0 ? double(s.samples) / s.seconds : 0;
    double raysPerSecond = s.seconds > 0 ? double(s.rays) / s.seconds : 0;
    std::fprintf(out, "time        %s (%.3f s)\n", ProgressReporter::formatDuration(s.seconds).c_str(), s.seconds);
    std::fprintf(out, "spp         %d\n", s.samplesPerPixel);
    std::fprintf(out, "samples/s   %.4g M\n", samplesPerSecond * 1e-6);
    std::fprintf(out, "rays/s      %.4g M (%llu rays)\n", raysPerSecond * 1e-6, (unsigned long long)s.rays);
    std::fprintf(out, "invalid     %llu samples (NaN/Inf/negative, dropped)\n",
                 (unsigned long long)s.invalidSamples);
}

void writeStatsJson(const std::string& path, const RenderStats& s, const OutputInfo& info, double buildSeconds,
                    const std::vector<std::pair<std::string, std::string>>& extra) {
    std::ofstream f(path);
    if (!f) throw Error(path + ": cannot write statistics");
    f << "{\n"
      << "  \"scene\": \"" << info.scene << "\",\n"
      << "  \"integrator\": \"" << info.integrator << "\",\n"
      << "  \"accel\": \"" << info.accel << "\",\n"
      << "  \"seed\": " << info.seed << ",\n"
      << "  \"seconds\": " << s.seconds << ",\n"
      << "  \"accel_build_seconds\": " << buildSeconds << ",\n"
      << "  \"spp\": " << s.samplesPerPixel << ",\n"
      << "  \"samples\": " << s.samples << ",\n"
      << "  \"rays\": " << s.rays << ",\n"
      << "  \"samples_per_second\": " << (s.seconds > 0 ? double(s.samples) / s.seconds : 0) << ",\n"
      << "  \"rays_per_second\": " << (s.seconds > 0 ? double(s.rays) / s.seconds : 0) << ",\n"
      << "  \"invalid_samples\": " << s.invalidSamples << ",\n"
      << "  \"cancelled\": " << (s.cancelled ? "true" : "false");
    for (const auto& [key, value] : extra) f << ",\n  \"" << key << "\": " << value;
    f << "\n}\n";
}

namespace {
constexpr char kCheckpointMagic[8] = {'C', 'A', 'U', 'S', 'C', 'K', 'P', '1'};
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary);
        if (!f) throw Error(tmp + ": cannot write checkpoint");
        write(f);
        if (!f) throw Error(tmp + ": writing the checkpoint failed");
    }
    std::filesystem::rename(tmp, path);  // atomic: a kill never leaves a half-written checkpoint
}

void saveCheckpoint(const std::string& path, const Film& film, uint64_t seed) {
    writeFileAtomically(path, [&](std::ostream& f) {
        f.write(kCheckpointMagic, sizeof kCheckpointMagic);
        f.write(reinterpret_cast<const char*>(&seed), sizeof seed);
        film.save(f);
    });
}

void loadCheckpoint(const std::string& path, Film& film, uint64_t seed) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw Error(path + ": cannot read checkpoint");
    char magic[8] = {};
    uint64_t savedSeed = 0;
    f.read(magic, sizeof magic);
    f.read(reinterpret_cast<char*>(&savedSeed), sizeof savedSeed);
    if (!f || std::string(magic, 8) != std::string(kCheckpointMagic, 8))
        throw Error(path + ": not a caustica checkpoint");
    if (savedSeed != seed)
        throw Error(path + ": checkpoint was rendered with --seed " + std::to_string(savedSeed) +
                    "; resume with the same seed");
    film.load(f);
}

}  // namespace caustica::cli
