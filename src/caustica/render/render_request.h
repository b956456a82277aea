// render_request.h — what a caller asks of a render besides the scene: integrator, budgets,
// device and execution choices, integrator overrides. The CLI and (later) the Python module fill
// it; render/ resolves it against the scene (Renderer).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/scene/integrator_spec.h"
#include "caustica/scene/stereo_rig.h"

namespace caustica {

struct RenderRequest {
    std::string integrator;         // "" = the scene's <integrator>
    std::optional<uint64_t> seed;   // default: the scene's sampler seed
    /// Budgets, totals of the whole render across resumes. Samples per pixel (mutations per
    /// pixel for mlt); with neither set, the scene's sample_count.
    int samplesPerPixel = 0;
    double timeLimit = 0;           // seconds of rendering
    int samplesPerPass = 0;         // pass-based integrators; 0: about 256k samples a pass
    std::optional<std::pair<int, int>> resolution;  // replaces the film's size (and any crop)
    std::map<std::string, std::string> defines;     // the -D values the scene was loaded with
    std::string device = "auto";    // cpu | cuda | auto
    /// The GPU to render on (0..count-1); -1: under an MPI launcher, the rank's local rank modulo
    /// the host's GPUs (one GPU per rank), else the CUDA default (GPU 0 or CUDA_VISIBLE_DEVICES').
    int gpu = -1;
    AccelKind accel = AccelKind::Embree;  // the CPU's ray tracer (a GPU traces the own BVH)
    /// The widest instruction set Embree may use (embree_isa.h): auto leaves it free on CPUs with
    /// AVX-512 whose clock it does not lower and on AMD Zen 3, else caps it at SSE4.2.
    EmbreeIsa embreeIsa = EmbreeIsa::Auto;
    /// CPU path tracer: wavefront | megakernel (the same image). The wavefront is the default: on
    /// every bundled scene it is at least as fast as the megakernel at 1 and 2 threads with Embree
    /// (the default accel; with the own BVH, packets of one ray, the two tie), and with AOVs it
    /// shares its camera rays' hits as the megakernel does (docs/PERFORMANCE.md, 2026-11-27).
    std::string pathMode = "wavefront";
    /// GPU path tracer: wavefront | megakernel (the same image up to rounding). The wavefront is
    /// the default: on an H200 it drew 1.31x the megakernel's samples/s on cornell-box and 2.09x
    /// on cornell-water, and rendered a 1280x720 stereo pair in half the time (docs/PERFORMANCE.md,
    /// "the first run on a GPU").
    std::string gpuMode = "wavefront";
    /// The integrator's parameters set on the command line (integrator_registry.h lists each
    /// integrator's options); they take the place of the scene's of the same name.
    std::vector<IntegratorParam> integratorParams;
    /// AOVs asked for on the command line (--aov "dd.y:depth,nn:sh_normal"); they replace the
    /// scene's aov integrator's list. "" = the scene's (if any).
    std::string aovs;
    /// `render --denoise`: add the denoiser's guide AOVs (render_denoise.h) to the AOVs.
    bool denoiseGuides = false;
    /// A stereo pair: the scene's camera becomes a rig and the film holds both eyes side by side
    /// (scene/stereo_rig.h, docs/STEREO.md). Mode Off: mono.
    StereoSettings stereo;
};

}  // namespace caustica
