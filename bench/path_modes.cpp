// path_modes.cpp — the CPU path tracer's two execution modes (megakernel, wavefront) against each
// other in one process, passes interleaved A B B A so that both see the same machine load: on a
// shared machine whose load moves by 10-30% between whole renders, short interleaved passes give
// a ratio that separate renders cannot. CPU seconds of the process per pass (both modes make the
// same image: pass_driver.h); the median of each mode's passes and their ratio.
//
//     path_modes SCENE.xml [--res WxH] [--spp-per-pass K] [--rounds N] [--threads T] [--accel embree|bvh]
//
// max_depth 16, rr_depth 5, emitters visible (the bundled scenes' settings).
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/launch.h"
#include "caustica/util/error.h"

namespace {

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) try {
    using namespace caustica;
    if (argc < 2) {
        std::fprintf(stderr, "usage: path_modes SCENE.xml [--res WxH] [--spp-per-pass K] [--rounds N] "
                             "[--threads T] [--accel embree|bvh]\n");
        return 2;
    }
    std::string res = "128x128", accelName = "embree";
    int k = 1, rounds = 40, threads = 1;
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string a = argv[i], v = argv[i + 1];
        if (a == "--res") res = v;
        else if (a == "--spp-per-pass") k = std::atoi(v.c_str());
        else if (a == "--rounds") rounds = std::atoi(v.c_str());
        else if (a == "--threads") threads = std::atoi(v.c_str());
        else if (a == "--accel") accelName = v;
        else throw Error("path_modes: unknown option " + a);
    }
    const size_t x = res.find('x');
    if (x == std::string::npos || k < 1 || rounds < 1 || threads < 1 || (accelName != "embree" && accelName != "bvh"))
        throw Error("path_modes: bad --res, --spp-per-pass, --rounds, --threads or --accel");
    const int width = std::atoi(res.substr(0, x).c_str()), height = std::atoi(res.substr(x + 1).c_str());
    tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism, size_t(threads));

    const Scene scene = loadScene(argv[1], {{"width", std::to_string(width)}, {"height", std::to_string(height)}});
    const Accel accel(scene, accelName == "bvh" ? AccelKind::Bvh : AccelKind::Embree);
    PathSettings settings;
    settings.maxDepth = 16;
    settings.rrDepth = 5;
    const PathMode modes[2] = {PathMode::Megakernel, PathMode::Wavefront};
    std::unique_ptr<PassDriver> drivers[2];
    for (int m = 0; m < 2; ++m) drivers[m] = makePathPass<CpuExec>(scene, accel, settings, modes[m]);
    SamplePass pass(scene.film.width, scene.film.height, k);

    std::vector<double> seconds[2];
    for (int r = 0; r < rounds; ++r)
        for (int m : {0, 1, 1, 0}) {  // A B B A: a drift in load hits both modes alike
            const double start = processCpuSeconds();
            drivers[m]->render(1, r * k, pass);
            seconds[m].push_back(processCpuSeconds() - start);
        }
    const double mk = median(seconds[0]), wf = median(seconds[1]);
    std::printf("%s %dx%d, %d spp per pass, %d rounds, %d threads, %s: median CPU s per pass megakernel %.4f, "
                "wavefront %.4f, wavefront speed / megakernel %.3f\n",
                argv[1], scene.film.width, scene.film.height, k, rounds, threads, accelName.c_str(), mk, wf, mk / wf);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
}
