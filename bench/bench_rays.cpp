// bench_rays.cpp — ray throughput: the own BVH's traversals (full stack, short stack, stackless)
// against Embree on the same rays, on one thread or several.
//
// Ray sets, precomputed once per scene and shared by both backends:
//   camera  one primary ray per pixel centre (closest hit)
//   bounce  cosine-distributed diffuse rays from the camera rays' first hits (closest hit)
//   shadow  any-hit rays from the same hit points to the light (or a point above the scene)
// Scenes: a procedural displaced icosphere (327,680 triangles) on a ground quad, and
// scenes/cornell-water/scene.xml and scenes/cornell-box/scene.xml when they load (each skipped
// with the reason printed otherwise).
// Backends: the own BVH's three traversals; Embree as caustica builds it (RTC_SCENE_FLAG_ROBUST,
// the instruction set `auto` picks for this CPU, embree_isa.h); Embree with its widest kernels
// (`embree-widest`, the same where auto picks them; on a CPU where auto caps Embree at SSE4.2 it
// shows what the cap costs or saves rays alone); and, for reference only, Embree without the
// robust flag (`embree-not-robust`, what Mitsuba 3 builds: faster, but it lets rays through shared
// mesh edges, tests/accel/watertight_test.cpp), so that the price of watertightness is measured
// beside the rest.
//
//   bench_rays [--threads=1,2] [--benchmark_filter=...] [--benchmark_repetitions=N]
// ends with a table: scene, ray type, threads, Mrays/s of each BVH traversal and of both Embree
// builds, and the ratios of the short-stack and stackless rates to the full-stack one, of the
// full stack to robust Embree and of non-robust to robust Embree. --threads lists the
// thread counts to run every benchmark with (default 1); with T threads each traces every T-th
// block of rays (see traceRays) and the rate is rays per second of wall time.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "caustica/accel/bvh.h"
#include "caustica/accel/embree_accel.h"
#include "caustica/accel/intersector.h"
#include "caustica/scene/camera.h"
#include "caustica/scene/interaction.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"
#include "bench_scenes.h"

#if __has_include("caustica/io/scene_loader.h")
#include "caustica/io/scene_loader.h"
#define CAUSTICA_BENCH_HAS_LOADER 1
#endif

using namespace caustica;

namespace {

struct BenchScene {
    std::string name;
    Scene scene;
    Bvh bvh;
    std::unique_ptr<EmbreeScene> embree;          // as caustica renders: robust
    std::unique_ptr<EmbreeScene> embreeWidest;     // robust, Embree's widest kernels
    std::unique_ptr<EmbreeScene> embreeNotRobust;  // reference only: leaks at shared edges
    std::vector<Ray> camera, bounce, shadow;
};

/// The shared ray sets (bench_scenes.h) of the scene.
void makeRays(BenchScene& b) {
    bench::RaySets sets = bench::makeRaySets(b.scene, b.bvh);
    b.camera = std::move(sets.camera);
    b.bounce = std::move(sets.bounce);
    b.shadow = std::move(sets.shadow);
}

std::vector<std::unique_ptr<BenchScene>> gScenes;

/// Rays per block handed to one thread: large enough that neighbouring (coherent) rays stay on
/// one thread, small enough that both threads get a similar mix of cheap and expensive rays.
constexpr size_t kRaysPerBlock = 256;

/// Traces the benchmark's share of `rays`: with T threads, thread i takes blocks i, i + T, ...
/// Each thread counts its hits in a local variable (no shared cache line is written).
template <class Intersector>
void traceRays(benchmark::State& state, const Intersector& it, const std::vector<Ray>& rays,
               bool anyHit) {
    const size_t threads = size_t(state.threads()), first = size_t(state.thread_index());
    uint64_t hits = 0, traced = 0;
    for (auto _ : state) {
        hits = traced = 0;
        for (size_t block = first * kRaysPerBlock; block < rays.size();
             block += threads * kRaysPerBlock) {
            const size_t end = std::min(rays.size(), block + kRaysPerBlock);
            traced += end - block;
            if (anyHit) {
                for (size_t i = block; i < end; ++i) hits += it.occluded(rays[i]);
            } else {
                for (size_t i = block; i < end; ++i) {
                    Hit hit;
                    hits += it.intersect(rays[i], hit);
                }
            }
        }
        benchmark::DoNotOptimize(hits);
    }
    // Counters are summed over the threads and rates divided by the (wall, see registerScene)
    // time: rays/s is the rate of all threads together, hit% that of the whole set.
    const double total = double(state.iterations()) * double(traced);
    state.SetItemsProcessed(int64_t(total));
    state.counters["rays/s"] = benchmark::Counter(total, benchmark::Counter::kIsRate);
    state.counters["hit%"] = 100.0 * double(hits) / double(max<size_t>(rays.size(), 1));
}

double maxOf(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

/// Thread counts every benchmark runs with (--threads).
std::vector<int> gThreadCounts = {1};

/// Registers `run` once per thread count. One thread is timed in CPU time (robust against other
/// processes on a shared machine), several in wall time, so that rays/s is their total rate.
template <class Run>
void registerRays(const std::string& name, const Run& run) {
    for (const int threads : gThreadCounts) {
        auto* bench = benchmark::RegisterBenchmark(name.c_str(), run)
                          ->Unit(benchmark::kMillisecond)
                          ->MinTime(1.0)
                          ->ComputeStatistics("max", maxOf)
                          ->Threads(threads);
        if (threads > 1) bench->UseRealTime();
    }
}

void registerScene(const BenchScene& b) {
    const std::pair<const char*, const std::vector<Ray>*> sets[] = {
        {"camera", &b.camera}, {"bounce", &b.bounce}, {"shadow", &b.shadow}};
    for (const auto& [type, rays] : sets) {
        const bool anyHit = std::string(type) == "shadow";
        const std::string prefix = "rays/" + b.name + "/" + type + "/";
        auto addBvh = [&](const std::string& name, auto intersector) {
            intersector.bvh = b.bvh.view();
            intersector.scene = b.scene.view();
            registerRays(prefix + name, [intersector, rays, anyHit](benchmark::State& st) {
                traceRays(st, intersector, *rays, anyHit);
            });
        };
        addBvh("bvh", BvhIntersectorT<BvhTraversal::Stack>{});
        addBvh("bvh-short", BvhIntersectorT<BvhTraversal::ShortStack>{});
        addBvh("bvh-stackless", BvhIntersectorT<BvhTraversal::Stackless>{});
        registerRays(prefix + "embree", [&b, rays, anyHit](benchmark::State& st) {
            traceRays(st, b.embree->intersector(), *rays, anyHit);
        });
        registerRays(prefix + "embree-widest", [&b, rays, anyHit](benchmark::State& st) {
            traceRays(st, b.embreeWidest->intersector(), *rays, anyHit);
        });
        registerRays(prefix + "embree-not-robust", [&b, rays, anyHit](benchmark::State& st) {
            traceRays(st, b.embreeNotRobust->intersector(), *rays, anyHit);
        });
    }
}

/// Parses and removes --threads=1,2,... from argv (before Google Benchmark sees the arguments).
void parseThreadCounts(int& argc, char** argv) {
    const std::string flag = "--threads=";
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.rfind(flag, 0) != 0) {
            argv[kept++] = argv[i];
            continue;
        }
        gThreadCounts.clear();
        for (size_t pos = flag.size(); pos < arg.size();) {
            const size_t comma = std::min(arg.find(',', pos), arg.size());
            gThreadCounts.push_back(std::max(1, std::atoi(arg.substr(pos, comma - pos).c_str())));
            pos = comma + 1;
        }
        if (gThreadCounts.empty()) gThreadCounts = {1};
    }
    argc = kept;
}

/// Resident memory of the process (Linux; 0 elsewhere): Embree reports no size of its BVH, so
/// the bench takes the growth across its build.
size_t residentBytes() {
    size_t pages = 0, resident = 0;
    if (FILE* f = std::fopen("/proc/self/statm", "r")) {
        if (std::fscanf(f, "%zu %zu", &pages, &resident) != 2) resident = 0;
        std::fclose(f);
    }
    return resident * 4096;
}

void addScene(std::string name, Scene scene) {
    auto b = std::make_unique<BenchScene>();
    b->name = std::move(name);
    b->scene = std::move(scene);
    b->bvh = buildBvh(b->scene);
    const size_t rssBefore = residentBytes();
    b->embree = std::make_unique<EmbreeScene>(b->scene);
    const size_t embreeBytes = residentBytes() - rssBefore;
    EmbreeSceneOptions widest;
    widest.isa = EmbreeIsa::Widest;
    b->embreeWidest = std::make_unique<EmbreeScene>(b->scene, widest);
    EmbreeSceneOptions notRobust;
    notRobust.robust = false;
    b->embreeNotRobust = std::make_unique<EmbreeScene>(b->scene, notRobust);
    makeRays(*b);
    const BvhStats& s = b->bvh.stats;
    std::printf(
        "%s: %u triangles, %zu spheres; BVH %u nodes, depth %u, %.2f prims/leaf, SAH %.1f, "
        "%.1f MiB, built in %.0f ms; Embree built in %.0f ms, %.1f MiB (resident memory it "
        "added); rays: %zu camera, %zu bounce, %zu shadow\n",
        b->name.c_str(), uint32_t(b->scene.triangles.size()), b->scene.spheres.size(), s.nodeCount,
        s.maxDepth, s.averageLeafSize, s.sahCost, double(s.memoryBytes) / (1 << 20),
        s.buildMilliseconds, b->embree->buildMilliseconds(), double(embreeBytes) / (1 << 20),
        b->camera.size(), b->bounce.size(), b->shadow.size());
    gScenes.push_back(std::move(b));
}

/// Console output as usual, plus every run's rays/s kept for the final table. With
/// --benchmark_repetitions the table takes the "max" aggregate: contention on a shared machine
/// only ever slows a run down, so the best repetition is the least disturbed one.
class TableReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs) {
            auto it = run.counters.find("rays/s");
            if (run.error_occurred || it == run.counters.end()) continue;
            const std::string name = rateKey(run.run_name.function_name, int(run.threads));
            const int rank = run.run_type != Run::RT_Aggregate ? 1
                             : run.aggregate_name == "max"     ? 3
                             : run.aggregate_name == "median"  ? 2
                                                               : 0;
            if (rank == 0) continue;
            const double value = it->second.value;
            auto& [bestRank, rate] = rates_[name];
            if (rank > bestRank) {
                bestRank = rank;
                rate = value;
            } else if (rank == 1 && bestRank == 1) {
                rate = std::max(rate, value);  // repetitions without aggregates
            }
        }
    }
    /// rays/s of a benchmark with `threads` threads, or a negative value if it did not run.
    double rate(const std::string& name, int threads) const {
        auto it = rates_.find(rateKey(name, threads));
        return it == rates_.end() ? -1.0 : it->second.second;
    }

private:
    static std::string rateKey(const std::string& name, int threads) {
        return name + "/threads:" + std::to_string(threads);
    }
    std::map<std::string, std::pair<int, double>> rates_;  // name -> (source rank, rays/s)
};

}  // namespace

int main(int argc, char** argv) {
    parseThreadCounts(argc, argv);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    addScene("icosphere-330k", bench::makeProceduralScene(7));
    for (const char* name : {"cornell-water", "cornell-box"}) {
#ifdef CAUSTICA_BENCH_HAS_LOADER
        const std::string path = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/" + name + "/scene.xml";
        try {
            std::vector<std::string> warnings;
            addScene(name, loadScene(path, {{"width", "640"}, {"height", "640"}}, &warnings));
        } catch (const std::exception& e) {
            std::printf("%s skipped: %s\n", name, e.what());
        }
#else
        std::printf("%s skipped: caustica/io/scene_loader.h is not available\n", name);
#endif
    }
    for (const auto& b : gScenes) registerScene(*b);

    TableReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);

    std::printf("\n%-16s %-8s %7s %9s %9s %9s %9s %9s %9s %7s %7s %7s %7s %7s\n", "scene", "rays", "threads",
                "stack", "short", "stackless", "Embree", "Embree", "Embree", "short/", "sless/", "stack/",
                "stack/", "NR/");
    std::printf("%-16s %-8s %7s %9s %9s %9s %9s %9s %9s %7s %7s %7s %7s %7s\n", "", "", "", "Mrays/s", "Mrays/s",
                "Mrays/s", "Mrays/s", "W Mr/s", "NR Mr/s", "stack", "stack", "Embree", "EmbW", "Embree");
    auto fixed2 = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.2f", v);
        return std::string(buf);
    };
    // "-" for what did not run (--benchmark_filter).
    auto rate = [&](double v) { return v < 0 ? std::string("-") : fixed2(v * 1e-6); };
    auto ratio = [&](double a, double b) {
        return a < 0 || b < 0 ? std::string("-") : fixed2(a / b);
    };
    for (const auto& b : gScenes)
        for (const char* type : {"camera", "bounce", "shadow"})
            for (const int threads : gThreadCounts) {
                const std::string prefix = "rays/" + b->name + "/" + type + "/";
                const double stack = reporter.rate(prefix + "bvh", threads),
                             shortStack = reporter.rate(prefix + "bvh-short", threads),
                             stackless = reporter.rate(prefix + "bvh-stackless", threads),
                             emb = reporter.rate(prefix + "embree", threads),
                             embWidest = reporter.rate(prefix + "embree-widest", threads),
                             embNotRobust = reporter.rate(prefix + "embree-not-robust", threads);
                if (stack < 0 && shortStack < 0 && stackless < 0 && emb < 0 && embWidest < 0 && embNotRobust < 0)
                    continue;
                std::printf("%-16s %-8s %7d %9s %9s %9s %9s %9s %9s %7s %7s %7s %7s %7s\n", b->name.c_str(), type,
                            threads, rate(stack).c_str(), rate(shortStack).c_str(), rate(stackless).c_str(),
                            rate(emb).c_str(), rate(embWidest).c_str(), rate(embNotRobust).c_str(),
                            ratio(shortStack, stack).c_str(), ratio(stackless, stack).c_str(),
                            ratio(stack, emb).c_str(), ratio(stack, embWidest).c_str(), ratio(embNotRobust, emb).c_str());
            }
    benchmark::Shutdown();
    return 0;
}
