// render_outputs.h — what a render writes: images with metadata, statistics as text and JSON, and
// the checks that every path can be written, made before the first sample.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "caustica/film/image.h"
#include "caustica/io/image_io.h"
#include "caustica/render/stereo_outputs.h"
#include "caustica/scene/scene.h"

namespace caustica {

class Renderer;

/// Refuses, before any rendering, an image path caustica cannot write: an unknown extension, a
/// missing folder, a folder or file without write permission. Errors name `path`.
void checkImageOutputPath(const std::string& path);
/// Refuses a path (statistics, checkpoint) that cannot be written, naming it.
void checkWritablePath(const std::string& path, const char* what);
/// The output written when none is given: SCENE_NAME.png for an ldrfilm (as Mitsuba writes an
/// LDR film's image), SCENE_NAME.exr otherwise, in the current directory.
std::string defaultOutputPath(const std::string& scenePath, const FilmDesc& film);
/// Runs `write(tmp)` on a temporary name beside `path` (same extension) and renames it over
/// `path`, so a killed render never leaves a torn image; errors name `path`.
void writeImageThroughTemporary(const std::string& path, const std::function<void(const std::string&)>& write);
/// The render's metadata written into its images (spp, render time, integrator, seed, ...).
ImageMetadata renderImageMetadata(const Renderer& renderer);
/// Writes `image` to every path (.exr, .pfm: linear radiance with the render's metadata; .png:
/// 8-bit sRGB, or tone-mapped when the scene's film is an ldrfilm), each through a temporary file
/// and a rename. A render with AOVs writes them as layers of every .exr (io/exr_layers.h); a
/// stereo render (`stereo.enabled`, stereo_outputs.h) writes each .exr as its stereo EXR(s) and,
/// when asked, the anaglyph.
void writeRenderImages(const std::vector<std::string>& paths, const Image& image, const Renderer& renderer,
                       const StereoOutputs& stereo = {});
/// Collective over the ranks of a distributed render (Renderer::stats): every rank calls it; a
/// null `out` prints nothing.
void printRenderSummary(const Renderer& renderer, std::FILE* out);
/// The statistics as JSON (the integrator's own entries included), written atomically; over
/// several ranks also "ranks" and "per_rank" (samples, rays, seconds). Collective: every rank
/// calls it, rank 0 writes.
void writeRenderStatsJson(const std::string& path, const Renderer& renderer, bool cancelled);

}  // namespace caustica
