// bench_gpu_rays.cu — GPU throughput of the own BVH and of the GPU path tracer (issue 4).
//
//  1. rays/s of camera, shadow (any hit) and diffuse-bounce (closest hit) rays for each BVH
//     traversal variant (accel/bvh_traversal.h: stack, short stack, stackless), one thread per
//     ray, on the 327,680-triangle displaced icosphere and on scenes/cornell-water at 640 x 640:
//     the ray sets of bench_rays (bench_scenes.h), so CPU and GPU figures compare directly. The
//     three variants must return the same hits; the table says whether they did.
//  2. path-tracing samples/s of the megakernel against the wavefront (the pass drivers, pass_driver.h) on
//     scenes/cornell-box and scenes/cornell-water: one pass of K samples per pixel per run,
//     download to the host included (what `caustica render --device cuda` pays per pass).
// Each figure is the best of --reps timed runs after one warm-up (timed with CUDA events for the
// ray kernels, with the host clock for the passes). Prints the tables and writes them as CSV.
// Without a CUDA GPU it prints why and exits 0, measuring nothing.
//
//   bench_gpu_rays [--reps N] [--spp K] [--res WxH] [--csv FILE]   (defaults 10, 16, 320x320,
//                                                                     bench_gpu_rays.csv)
#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_scenes.h"
#include "caustica/accel/bvh.h"
#include "caustica/accel/intersector.h"
#include "caustica/accel/accel.h"
#include "caustica/accel/device_scene.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/integrators/path/path_settings.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/buffer.h"
#include "caustica/util/error.h"
#include "cuda/cuda_backend.h"
#include "cuda/cuda_check.h"
#include "cuda/parallel_for_cuda.h"

namespace caustica::bench_gpu {

// Extended (__device__) lambdas need an enclosing function with external linkage: the kernel
// launchers live here, outside any unnamed namespace.

/// One thread per ray: hits[i] = primitive id + 1 of the closest hit (0 on a miss), or for
/// `anyHit` 1 if the ray is occluded.
template <BvhTraversal Traversal>
void traceRays(const BvhView& bvh, const SceneView& scene, const Ray* rays, size_t n, bool anyHit,
               uint32_t* hits) {
    const BvhIntersectorT<Traversal> it{bvh, scene};
    if (anyHit) {
        parallelForCuda(
            "bench.gpu.occluded", n,
            [=] __device__(size_t i) { hits[i] = it.occluded(rays[i]) ? 1u : 0u; }, 128);
    } else {
        parallelForCuda(
            "bench.gpu.intersect", n,
            [=] __device__(size_t i) {
                Hit hit;
                hits[i] = it.intersect(rays[i], hit) ? hit.primId + 1 : 0u;
            },
            128);
    }
}

}  // namespace caustica::bench_gpu

namespace {

using namespace caustica;

struct Options {
    int reps = 10;
    int spp = 16;
    int width = 320, height = 320;
    std::string csv = "bench_gpu_rays.csv";
};

/// Best GPU time (ms) of `reps` runs of `launch` after one warm-up, timed with CUDA events.
template <class Launch>
double bestGpuMs(int reps, const Launch& launch) {
    launch();
    CA_CUDA_CHECK(cudaDeviceSynchronize());
    cudaEvent_t start, stop;
    CA_CUDA_CHECK(cudaEventCreate(&start));
    CA_CUDA_CHECK(cudaEventCreate(&stop));
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < reps; ++r) {
        CA_CUDA_CHECK(cudaEventRecord(start));
        launch();
        CA_CUDA_CHECK(cudaEventRecord(stop));
        CA_CUDA_CHECK(cudaEventSynchronize(stop));
        float ms = 0;
        CA_CUDA_CHECK(cudaEventElapsedTime(&ms, start, stop));
        best = std::min(best, double(ms));
    }
    cudaEventDestroy(start);
    cudaEventDestroy(stop);
    return best;
}

/// Best wall time (ms) of `reps` runs of `run` after one warm-up (for work that synchronizes).
template <class Run>
double bestHostMs(int reps, const Run& run) {
    run();
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r < reps; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        run();
        const auto t1 = std::chrono::steady_clock::now();
        best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    return best;
}

const char* kVariantNames[] = {"stack", "short-stack", "stackless"};

struct RayRow {
    std::string scene, rays;
    size_t count = 0;
    double ms[3] = {-1, -1, -1};  // per variant
    double hitPercent = 0;
    bool agree = true;  // the three variants returned the same hits
};

struct PathRow {
    std::string scene;
    int width = 0, height = 0, spp = 0;
    double ms[2] = {-1, -1};  // megakernel, wavefront
    uint64_t rays[2] = {0, 0};
};

/// Times the three traversal variants on one ray set (already on the device).
RayRow benchRaySet(const std::string& sceneName, const char* rayName, const DeviceScene& gpu,
                   const std::vector<Ray>& hostRays, bool anyHit, int reps) {
    RayRow row;
    row.scene = sceneName;
    row.rays = rayName;
    row.count = hostRays.size();
    if (hostRays.empty()) return row;
    const Buffer<Ray> rays(Device::cuda(), hostRays);
    Buffer<uint32_t> hits(Device::cuda(), hostRays.size());
    std::vector<uint32_t> first(hostRays.size()), other(hostRays.size());
    for (int v = 0; v < 3; ++v) {
        auto launch = [&] {
            switch (v) {
                case 0:
                    bench_gpu::traceRays<BvhTraversal::Stack>(
                        gpu.bvhView(), gpu.view(), rays.data(), rays.size(), anyHit, hits.data());
                    break;
                case 1:
                    bench_gpu::traceRays<BvhTraversal::ShortStack>(
                        gpu.bvhView(), gpu.view(), rays.data(), rays.size(), anyHit, hits.data());
                    break;
                default:
                    bench_gpu::traceRays<BvhTraversal::Stackless>(
                        gpu.bvhView(), gpu.view(), rays.data(), rays.size(), anyHit, hits.data());
                    break;
            }
        };
        row.ms[v] = bestGpuMs(reps, launch);
        std::vector<uint32_t>& out = v == 0 ? first : other;
        hits.copyToHost(Span<uint32_t>(out.data(), out.size()));
        if (v == 0) {
            size_t hitCount = 0;
            for (uint32_t h : first) hitCount += h != 0;
            row.hitPercent = 100.0 * double(hitCount) / double(first.size());
        } else if (other != first) {
            row.agree = false;
        }
    }
    return row;
}

void benchRays(const std::string& name, const Scene& scene, int reps, std::vector<RayRow>& rows) {
    const Bvh bvh = buildBvh(scene);  // parent links included: short-stack and stackless need them
    const bench::RaySets sets = bench::makeRaySets(scene, bvh);
    const DeviceScene gpu(scene, bvh, Device::cuda());
    std::printf("%s: %u triangles, %zu spheres; %zu camera, %zu shadow, %zu bounce rays\n",
                name.c_str(), uint32_t(scene.triangles.size()), scene.spheres.size(),
                sets.camera.size(), sets.shadow.size(), sets.bounce.size());
    rows.push_back(benchRaySet(name, "camera", gpu, sets.camera, false, reps));
    rows.push_back(benchRaySet(name, "shadow", gpu, sets.shadow, true, reps));
    rows.push_back(benchRaySet(name, "bounce", gpu, sets.bounce, false, reps));
}

PathRow benchPaths(const std::string& name, const Scene& scene, const Options& opt) {
    PathRow row;
    row.scene = name;
    row.width = scene.film.width;
    row.height = scene.film.height;
    row.spp = opt.spp;
    const Accel accel(scene, AccelKind::Bvh);
    IntegratorParams params(scene.integrator);
    const PathSettings settings = readPathSettings(params);
    const PathMode modes[2] = {PathMode::Megakernel, PathMode::Wavefront};
    for (int m = 0; m < 2; ++m) {
        const std::unique_ptr<PassDriver> renderer = makePathPass<GpuExec>(scene, accel, settings, modes[m]);
        SamplePass pass(scene.film.width, scene.film.height, opt.spp);
        int first = 0;
        row.ms[m] = bestHostMs(std::max(1, opt.reps / 3), [&] {
            row.rays[m] = renderer->render(scene.seed, first, pass);
            first += opt.spp;
        });
    }
    return row;
}

std::string fixed(double v, int digits = 2) {
    if (v < 0) return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

bool parseOptions(int argc, char** argv, Options& opt) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool hasValue = i + 1 < argc;
        if (a == "--reps" && hasValue) {
            opt.reps = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--spp" && hasValue) {
            opt.spp = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--res" && hasValue) {
            if (std::sscanf(argv[++i], "%dx%d", &opt.width, &opt.height) != 2 || opt.width <= 0 ||
                opt.height <= 0)
                return false;
        } else if (a == "--csv" && hasValue) {
            opt.csv = argv[++i];
        } else {
            return false;
        }
    }
    return true;
}

void printAndWrite(const std::vector<RayRow>& rays, const std::vector<PathRow>& paths,
                   const Options& opt, const std::string& device) {
    std::FILE* csv = std::fopen(opt.csv.c_str(), "w");
    if (!csv) std::fprintf(stderr, "bench_gpu_rays: cannot write %s\n", opt.csv.c_str());
    if (csv) std::fprintf(csv, "table,scene,what,variant,count,best_ms,rate_per_s,extra\n");

    std::printf("\n== GPU ray throughput (%s; best of %d; Mrays/s)\n", device.c_str(), opt.reps);
    std::printf("%-16s %-7s %9s %10s %10s %10s %7s %7s %6s %s\n", "scene", "rays", "count", "stack",
                "short", "stackless", "short/", "sless/", "hit%", "hits");
    std::printf("%-16s %-7s %9s %10s %10s %10s %7s %7s %6s %s\n", "", "", "", "", "", "", "stack",
                "stack", "", "");
    for (const RayRow& r : rays) {
        double rate[3];
        for (int v = 0; v < 3; ++v) {
            rate[v] = r.ms[v] > 0 ? double(r.count) / (r.ms[v] * 1e-3) : -1;
            if (csv && r.ms[v] > 0)
                std::fprintf(csv, "rays,%s,%s,%s,%zu,%.6f,%.6e,hit%%=%.3f\n", r.scene.c_str(),
                             r.rays.c_str(), kVariantNames[v], r.count, r.ms[v], rate[v],
                             r.hitPercent);
        }
        auto ratio = [](double a, double b) { return a > 0 && b > 0 ? fixed(a / b) : "-"; };
        std::printf("%-16s %-7s %9zu %10s %10s %10s %7s %7s %6s %s\n", r.scene.c_str(),
                    r.rays.c_str(), r.count, fixed(rate[0] * 1e-6).c_str(),
                    fixed(rate[1] * 1e-6).c_str(), fixed(rate[2] * 1e-6).c_str(),
                    ratio(rate[1], rate[0]).c_str(), ratio(rate[2], rate[0]).c_str(),
                    fixed(r.hitPercent, 1).c_str(), r.agree ? "same" : "DIFFER");
    }

    std::printf(
        "\n== GPU path tracing (%s; one pass of K spp per run, download included; "
        "Msamples/s)\n",
        device.c_str());
    std::printf("%-16s %9s %4s %12s %12s %10s %12s %12s\n", "scene", "res", "spp", "megakernel",
                "wavefront", "wave/mega", "Mrays/s mk", "Mrays/s wf");
    for (const PathRow& p : paths) {
        const double samples = double(p.width) * p.height * p.spp;
        double sps[2], rps[2];
        for (int m = 0; m < 2; ++m) {
            sps[m] = p.ms[m] > 0 ? samples / (p.ms[m] * 1e-3) : -1;
            rps[m] = p.ms[m] > 0 ? double(p.rays[m]) / (p.ms[m] * 1e-3) : -1;
            if (csv && p.ms[m] > 0)
                std::fprintf(csv, "path,%s,%dx%dx%d,%s,%.0f,%.6f,%.6e,rays_per_s=%.6e\n",
                             p.scene.c_str(), p.width, p.height, p.spp,
                             m == 0 ? "megakernel" : "wavefront", samples, p.ms[m], sps[m], rps[m]);
        }
        const std::string res = std::to_string(p.width) + "x" + std::to_string(p.height);
        std::printf("%-16s %9s %4d %12s %12s %10s %12s %12s\n", p.scene.c_str(), res.c_str(), p.spp,
                    fixed(sps[0] * 1e-6).c_str(), fixed(sps[1] * 1e-6).c_str(),
                    sps[0] > 0 && sps[1] > 0 ? fixed(sps[1] / sps[0]).c_str() : "-",
                    fixed(rps[0] * 1e-6).c_str(), fixed(rps[1] * 1e-6).c_str());
    }
    if (csv) {
        std::fclose(csv);
        std::printf("\nCSV: %s\n", opt.csv.c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    Options opt;
    if (!parseOptions(argc, argv, opt)) {
        std::fprintf(stderr,
                     "usage: bench_gpu_rays [--reps N] [--spp K] [--res WxH] [--csv FILE]\n");
        return 2;
    }
    registerCudaBackend();
    if (cudaDeviceCountOrZero() == 0) {
        std::printf(
            "bench_gpu_rays: no CUDA GPU found (or no driver): skipped, nothing measured\n");
        return 0;
    }
    const std::string device = cudaDeviceDescription();
    std::printf("bench_gpu_rays on %s\n", device.c_str());
    try {
        std::vector<RayRow> rays;
        benchRays("icosphere-330k", bench::makeProceduralScene(7), opt.reps, rays);
        const std::string dir = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/";
        std::vector<std::string> warnings;
        benchRays("cornell-water",
                  loadScene(dir + "cornell-water/scene.xml", {{"width", "640"}, {"height", "640"}},
                            &warnings),
                  opt.reps, rays);
        std::vector<PathRow> paths;
        const std::map<std::string, std::string> res = {{"width", std::to_string(opt.width)},
                                                        {"height", std::to_string(opt.height)}};
        for (const char* name : {"cornell-box", "cornell-water"})
            paths.push_back(
                benchPaths(name, loadScene(dir + name + "/scene.xml", res, &warnings), opt));
        printAndWrite(rays, paths, opt, device);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_gpu_rays: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
