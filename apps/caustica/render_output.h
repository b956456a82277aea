// render_output.h — what `caustica render` writes: images with metadata, statistics, checkpoints.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "caustica/film/film.h"
#include "caustica/integrators/render_loop.h"

namespace caustica::cli {

struct OutputInfo {
    std::string scene, integrator, accel;
    uint64_t seed = 0;
    ToneMapDesc tonemap;  // the scene film's: an ldrfilm tone-maps its PNG outputs
};

/// Refuses an output path whose extension caustica cannot write, before any rendering is done.
void checkOutputPath(const std::string& path);
/// The output written when none is given: SCENE_NAME.png for an ldrfilm (as Mitsuba writes an
/// LDR film's image), SCENE_NAME.exr otherwise, in the current directory.
std::string defaultOutputPath(const std::string& scenePath, const FilmDesc& film);
/// Writes the developed film to every path (.exr, .pfm: linear radiance; .png: 8-bit sRGB, or
/// tone-mapped by info.tonemap when the film is an ldrfilm).
void writeOutputs(const std::vector<std::string>& paths, const Film& film, const RenderStats& stats,
                  const OutputInfo& info);
/// The same for an image developed elsewhere (Metropolis); `spp` is its samples (or mutations)
/// per pixel as written to the metadata.
void writeImageOutputs(const std::vector<std::string>& paths, const Image& image, const std::string& spp,
                       const RenderStats& stats, const OutputInfo& info);
void printSummary(const RenderStats& stats, std::FILE* out);
/// `extra`: further (key, JSON value) entries, e.g. an integrator's own figures.
void writeStatsJson(const std::string& path, const RenderStats& stats, const OutputInfo& info, double buildSeconds,
                    const std::vector<std::pair<std::string, std::string>>& extra = {});

/// Checkpoints: the film's accumulated sums plus the seed, written atomically (temp + rename).
void saveCheckpoint(const std::string& path, const Film& film, uint64_t seed);
void loadCheckpoint(const std::string& path, Film& film, uint64_t seed);
/// Writes `path` through `write` into path.tmp, then renames it: a kill never leaves a
/// half-written file.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace caustica::cli
