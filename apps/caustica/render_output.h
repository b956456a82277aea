// render_output.h — what `caustica render` writes: images with metadata, statistics, checkpoints.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "caustica/film/film.h"
#include "caustica/integrators/render_loop.h"

namespace caustica::cli {

struct OutputInfo {
    std::string scene, integrator, accel;
    uint64_t seed = 0;
};

/// Refuses an output path whose extension caustica cannot write, before any rendering is done.
void checkOutputPath(const std::string& path);
void writeOutputs(const std::vector<std::string>& paths, const Film& film, const RenderStats& stats,
                  const OutputInfo& info);
void printSummary(const RenderStats& stats, std::FILE* out);
void writeStatsJson(const std::string& path, const RenderStats& stats, const OutputInfo& info, double buildSeconds);

/// Checkpoints: the film's accumulated sums plus the seed, written atomically (temp + rename).
void saveCheckpoint(const std::string& path, const Film& film, uint64_t seed);
void loadCheckpoint(const std::string& path, Film& film, uint64_t seed);

}  // namespace caustica::cli
