// spatial_bench_core.h — the measurement of the photon lookup structures (src/caustica/spatial/)
// shared by spatial_bench.cpp (CPU, g++) and bench_gpu_spatial.cu (GPU, nvcc): options, point
// sets, the structure list, the query kernels, the totals check and the CSV report. Everything
// that runs structures is a template on Exec (parallel/launch.h: CpuExec or GpuExec): the
// structures are built with S::build(exec, ...) on Exec's device, and the queries are one launch
// per query type over buffers in that device's memory. The point sets themselves always come from
// the CPU (uniform random, or a CPU SPPM render): they are only the input.
//
// Point sets (--sets, default all), each giving a "points" set (photons: one common radius) and a
// "spheres" set (visible points: each its own radius):
//   uniform        1,000,000 points uniform in the unit cube, radius 0.0193 (about 30 points per
//                  ball); 100,000 random query points; spheres: radii uniform in [0.5, 1.5] r
//   cornell-water  scenes/cornell-water/scene.xml at 256x256 \  after --iterations of an SPPM
//   glass-caustic  scenes/glass-caustic/scene.xml at 256x256  | render (CPU, direction gather):
//   water-1080p    scenes/cornell-water/scene.xml at 1920x1080 / SppmDriverBase::lookupInputs()
// Queries: points sets: "within" (forEachPointWithin at each query's radius) and "knn16"
// (kNearest, k = 16, max radius 2 r); spheres sets: "covering" (forEachSphereCovering) and
// "segment" (forEachSphereOnSegment, a random unit direction, length 10 x the median radius).
//
// Every figure is the best (minimum) of --repeat runs. Each query writes its result count and the
// sum of its result indices into per-query arrays, summed afterwards: the work cannot be optimised
// away, and the totals are a cheap correctness check: every structure must return exactly the
// same sets (point_set.h), so the totals of one set and query must agree between all structures
// (AgreementCheck; the programs exit with status 1 when they do not).
//
// The query kernel is an nvcc extended lambda: it lives in a function template of a named
// namespace (not an unnamed one), and the query type is a template parameter (if constexpr).
#pragma once

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/sppm/sppm_driver.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/spatial/hash_grid.h"
#include "caustica/spatial/kd_tree.h"
#include "caustica/spatial/multi_hash.h"
#include "caustica/spatial/point_set.h"
#include "caustica/spatial/uniform_grid.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"

namespace caustica::spatial_bench {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// ---- options ------------------------------------------------------------------------------------

struct Options {
    std::vector<std::string> sets;        // empty: all
    std::vector<std::string> structures;  // name prefixes; empty: all
    int repeat = 3;
    int iterations = 8;
    uint64_t photons = uint64_t(1) << 18;  // photon paths per iteration, unless the scene says
    int threads = 0;                       // 0: all cores
    double scale = 1;                      // point and query counts (and image area) times this
    std::string csv;                       // "": bench/results/<csvPrefix>-YYYY-MM-DD.csv
};

/// "a,b(c,d),e" -> a, b(c,d), e: commas inside parentheses belong to a structure's name.
inline std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items(1);
    int depth = 0;
    for (char c : text) {
        depth += c == '(' ? 1 : c == ')' ? -1 : 0;
        if (c == ',' && depth == 0)
            items.emplace_back();
        else
            items.back() += c;
    }
    std::erase(items, std::string());
    return items;
}

/// The program's name and its default CSV file's prefix (spatial_bench: "spatial").
struct Program {
    const char* name;
    const char* csvPrefix;
};

[[noreturn]] inline void usage(const Program& program, int status) {
    const std::string pad(std::string(program.name).size(), ' ');
    std::fprintf(
        status ? stderr : stdout,
        "usage: %s [--sets LIST] [--structures LIST] [--repeat N] [--iterations N]\n"
        "       %s [--photons N] [--threads N] [--scale X] [--csv FILE]\n"
        "  --sets        uniform,cornell-water,glass-caustic,water-1080p (default: all)\n"
        "  --structures  structure names or prefixes, e.g. kdtree,multihash (default: all)\n"
        "  --repeat      runs of each build and query; the best is reported (3)\n"
        "  --iterations  SPPM iterations before the scenes' point sets are taken (8)\n"
        "  --photons     photon paths per SPPM iteration (262144)\n"
        "  --threads     CPU worker threads (default: all cores)\n"
        "  --scale       point and query counts x X, image area x X (1; 0.1 for a smoke run)\n"
        "  --csv         output (default: bench/results/%s-YYYY-MM-DD.csv)\n",
        program.name, pad.c_str(), program.csvPrefix);
    std::exit(status);
}

inline bool knownSet(const std::string& name);

inline Options parseOptions(const Program& program, int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") usage(program, 0);
        if (i + 1 >= argc) usage(program, 2);
        const std::string value = argv[++i];
        try {
            if (arg == "--sets")
                o.sets = splitList(value);
            else if (arg == "--structures")
                o.structures = splitList(value);
            else if (arg == "--repeat")
                o.repeat = std::max(1, std::stoi(value));
            else if (arg == "--iterations")
                o.iterations = std::max(1, std::stoi(value));
            else if (arg == "--photons")
                o.photons = std::max<uint64_t>(1, std::stoull(value));
            else if (arg == "--threads")
                o.threads = std::max(1, std::stoi(value));
            else if (arg == "--scale")
                o.scale = std::stod(value);
            else if (arg == "--csv")
                o.csv = value;
            else
                usage(program, 2);
        } catch (const std::logic_error&) {  // stoi & co.: not a number
            std::fprintf(stderr, "%s %s: not a number\n", arg.c_str(), value.c_str());
            usage(program, 2);
        }
    }
    if (!(o.scale > 0 && o.scale <= 1)) {
        std::fprintf(stderr, "--scale must be in (0, 1]\n");
        usage(program, 2);
    }
    for (const std::string& name : o.sets)
        if (!knownSet(name)) {
            std::fprintf(stderr, "unknown set '%s'\n", name.c_str());
            usage(program, 2);
        }
    return o;
}

/// --threads as TBB's limit for as long as this lives (none for 0); count(): the threads the
/// CPU's kernels may use.
class CpuThreads {
public:
    explicit CpuThreads(int threads) {
        if (threads > 0) limit_.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
    }
    int count() const {
        return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    }

private:
    std::optional<tbb::global_control> limit_;
};

inline std::string todaysCsv(const Program& program) {
    const std::time_t now = std::time(nullptr);
    char date[16];
    std::strftime(date, sizeof date, "%Y-%m-%d", std::localtime(&now));
    return std::string(CAUSTICA_SOURCE_DIR) + "/bench/results/" + program.csvPrefix + "-" + date +
           ".csv";
}

// ---- point sets ---------------------------------------------------------------------------------

/// One set of points to build the structures over, with its queries (host memory).
struct BenchSet {
    std::string name;               // `set`: uniform/points, <scene>/photons, <source>/spheres
    std::vector<Vec3f> positions;   // the points (photons; visible points for spheres)
    std::vector<Float> radii;       // spheres: each point's radius; points: empty
    Float radius = 0;               // points: the common (build) radius
    std::vector<Vec3f> queries;     // ball centres, covered points or segment origins
    std::vector<Float> queryRadii;  // points: each query's gather radius
    std::vector<Vec3f> directions;  // spheres: each segment's unit direction
    Float segmentLength = 0;        // spheres: every segment's tMax

    bool spheres() const { return !radii.empty(); }
};

inline Float median(std::vector<Float> v) {
    if (v.empty()) return 0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

inline Vec3f extentOf(const std::vector<Vec3f>& points) {
    Bounds3f box;
    for (const Vec3f& p : points) box.extend(p);
    return box.empty() ? Vec3f(0) : box.diagonal();
}

/// The radius that sizes the structures: the common one, or the largest sphere's.
inline Float buildRadius(const BenchSet& s) {
    return s.spheres() ? *std::max_element(s.radii.begin(), s.radii.end()) : s.radius;
}

/// The typical ball of a query: the median sphere radius (spheres) or query radius (points).
inline Float typicalRadius(const BenchSet& s) {
    return median(s.spheres() ? s.radii : s.queryRadii);
}

/// `n` uniform values in [0, 1)^3 from stream `seed` (fixed: the same sets on every run).
inline std::vector<Vec3f> randomUnitCube(size_t n, uint64_t seed) {
    std::vector<Vec3f> p(n);
    for (size_t i = 0; i < n; ++i) {
        IndependentSampler s(i, 0, seed);
        const Float x = s.get1D(), y = s.get1D();
        p[i] = Vec3f(x, y, s.get1D());
    }
    return p;
}

inline std::vector<Vec3f> randomDirections(size_t n, uint64_t seed) {
    std::vector<Vec3f> d(n);
    for (size_t i = 0; i < n; ++i) {
        IndependentSampler s(i, 0, seed);
        d[i] = sampleUniformSphere(s.get2D());
    }
    return d;
}

/// The spheres set's segments: random directions, length 10 x the median sphere radius.
inline void addSegments(BenchSet& s) {
    s.directions = randomDirections(s.queries.size(), 0x5e6);
    s.segmentLength = 10 * median(s.radii);
}

inline size_t scaled(size_t n, double scale) {
    return std::max<size_t>(1, size_t(std::llround(double(n) * scale)));
}

/// 1M points in the unit cube and 100k queries. With --scale the radius grows by scale^(-1/3),
/// so that a ball still holds about 30 points and a smoke run exercises the same code paths.
inline std::vector<BenchSet> uniformSets(double scale) {
    const Float r = Float(0.0193 / std::cbrt(scale));
    BenchSet points;
    points.name = "uniform/points";
    points.positions = randomUnitCube(scaled(1000000, scale), 1);
    points.radius = r;
    points.queries = randomUnitCube(scaled(100000, scale), 2);
    points.queryRadii.assign(points.queries.size(), r);

    BenchSet spheres;
    spheres.name = "uniform/spheres";
    spheres.positions = points.positions;
    spheres.radii.resize(spheres.positions.size());
    for (size_t i = 0; i < spheres.radii.size(); ++i)
        spheres.radii[i] = r * (Float(0.5) + IndependentSampler(i, 0, 3).get1D());
    spheres.queries = points.queries;
    addSegments(spheres);
    return {std::move(points), std::move(spheres)};
}

struct SceneSource {
    const char* name;  // --sets
    const char* file;  // under the source tree
    int width, height;
};

inline constexpr SceneSource kScenes[] = {
    {"cornell-water", "scenes/cornell-water/scene.xml", 256, 256},
    {"glass-caustic", "scenes/glass-caustic/scene.xml", 256, 256},
    {"water-1080p", "scenes/cornell-water/scene.xml", 1920, 1080},
};

inline bool knownSet(const std::string& name) {
    bool known = name == "uniform";
    for (const SceneSource& src : kScenes) known = known || name == src.name;
    return known;
}

inline bool wanted(const Options& o, const std::string& set) {
    return o.sets.empty() || std::find(o.sets.begin(), o.sets.end(), set) != o.sets.end();
}

/// The scene's <integrator> parameters (max_depth, rr_depth, ...) read as sppm's, direction
/// gather (the default; the only one that stores photons), photon_count --photons x scale unless
/// the scene gives one.
inline SppmSettings sceneSppmSettings(const Scene& scene, const Options& o) {
    std::vector<IntegratorParam> overrides = {
        {"direction", IntegratorParam::Kind::Text, "gather", "spatial_bench"}};
    if (!IntegratorParams(scene.integrator).has("photon_count"))
        overrides.push_back({"photon_count", IntegratorParam::Kind::Text,
                             std::to_string(scaled(o.photons, o.scale)), "--photons"});
    IntegratorParams params = integratorParams(scene.integrator, "sppm", overrides);
    return readSppmSettings(params, PhotonMapper::Sppm);
}

/// Renders --iterations SPPM iterations of the scene on the CPU and takes the point sets of the
/// last one: the photons with the largest visible-point radius as the common radius, gathered at
/// the visible points with their own radii (what gatherPass does), and the visible points' spheres
/// with the photons as queries (what the deposit direction does).
inline std::vector<BenchSet> sceneSets(const SceneSource& src, const Options& o) {
    const double side = std::sqrt(o.scale);  // --scale: the image area
    const int w = std::max(1, int(std::lround(src.width * side)));
    const int h = std::max(1, int(std::lround(src.height * side)));
    Scene scene = loadScene(std::string(CAUSTICA_SOURCE_DIR) + "/" + src.file,
                            {{"width", std::to_string(w)}, {"height", std::to_string(h)}});
    const SppmSettings settings = sceneSppmSettings(scene, o);
    const auto start = Clock::now();
    SppmLookupInputs in;
    Float initialRadius = 0;
    {
        const Accel accel(scene, AccelKind::Embree);
        auto driver = makeSppmDriver<CpuExec>(scene, accel, settings, scene.seed);
        for (int i = 0; i < o.iterations; ++i) driver->iterate();
        in = driver->lookupInputs();
        initialRadius = driver->settings().initialRadius;  // the automatic one, once resolved
    }  // the driver's and the accel's memory go before the measurements
    std::printf(
        "%s: %s at %dx%d, sppm %d iterations of %llu photon paths (direction gather, "
        "initial radius %.4g) in %.1f s: %zu photons stored, %zu visible points\n",
        src.name, src.file, w, h, o.iterations, (unsigned long long)settings.photonCount,
        double(initialRadius), msSince(start) * 1e-3, in.photons.size(), in.visiblePoints.size());
    if (in.photons.empty() || in.visiblePoints.empty())
        throw Error(std::string(src.name) + ": no photons or no visible points");

    BenchSet photons;
    photons.name = std::string(src.name) + "/photons";
    photons.positions = in.photons;
    photons.radius = *std::max_element(in.visibleRadii.begin(), in.visibleRadii.end());
    photons.queries = in.visiblePoints;
    photons.queryRadii = in.visibleRadii;

    BenchSet spheres;
    spheres.name = std::string(src.name) + "/spheres";
    spheres.positions = std::move(in.visiblePoints);
    spheres.radii = std::move(in.visibleRadii);
    spheres.queries = std::move(in.photons);
    addSegments(spheres);
    return {std::move(photons), std::move(spheres)};
}

/// Calls f(set) for every selected set, in table order (the scenes' renders one at a time).
template <class F>
void forEachSet(const Options& o, F&& f) {
    if (wanted(o, "uniform"))
        for (const BenchSet& s : uniformSets(o.scale)) f(s);
    for (const SceneSource& src : kScenes) {
        if (!wanted(o, src.name)) continue;
        for (const BenchSet& s : sceneSets(src, o)) f(s);
    }
}

/// A point set and its queries in the memory of Exec's device, with the statistics its rows carry.
template <class Exec>
struct PreparedSet {
    const BenchSet& set;
    Buffer<Vec3f> positions;
    Buffer<Float> radii;
    Buffer<Vec3f> queries;
    Buffer<Float> queryRadii;
    Buffer<Vec3f> directions;
    Vec3f extent;
    Float radius = 0, medianRadius = 0;

    explicit PreparedSet(const BenchSet& s)
        : set(s),
          positions(Exec::device(), s.positions),
          radii(Exec::device(), s.radii),
          queries(Exec::device(), s.queries),
          queryRadii(Exec::device(), s.queryRadii),
          directions(Exec::device(), s.directions),
          extent(extentOf(s.positions)),
          radius(buildRadius(s)),
          medianRadius(typicalRadius(s)) {}
    PointSet points() const {
        return PointSet{positions.constSpan(), radii.constSpan(), set.radius};
    }
};

// ---- structures ---------------------------------------------------------------------------------

/// One configuration of structure S: its name in the table and how it is built (on the device
/// the list was made for).
template <class S>
struct Variant {
    std::string name;
    std::function<S(const PointSet&)> build;
};

/// Structure S with its default build on Exec's device, named `name`.
template <class S, class Exec>
std::vector<Variant<S>> defaults(Exec exec, const char* name) {
    return {{name, [exec](const PointSet& p) { return S::build(exec, p); }}};
}

/// MultiHash with the rule's alternatives (docs/PHOTON_LOOKUP.md): the density rule with
/// leafPoints {512, 4096, 32768} x pointsPerCell {4, 16, 64} (pointsPerCell 1 was measured 10-50x
/// slower and left out), the radius rule and the coarser of both at leafPoints 4096.
template <class Exec>
std::vector<Variant<MultiHash>> multiHashSweep(Exec exec) {
    std::vector<Variant<MultiHash>> sweep;
    auto add = [&](const char* name, MultiHashOptions options) {
        sweep.push_back({name, [exec, options](const PointSet& p) {
                             return MultiHash::build(exec, p, options);
                         }});
    };
    for (uint32_t leafPoints : {512u, 4096u, 32768u})
        for (Float pointsPerCell : {Float(4), Float(16), Float(64)}) {
            char name[64];
            std::snprintf(name, sizeof name, "multihash(L=%u,P=%g)", leafPoints,
                          double(pointsPerCell));
            add(name, MultiHashOptions{leafPoints, pointsPerCell});
        }
    add("multihash(L=4096,radius)", MultiHashOptions{4096, 4, MultiHashCellRule::Radius});
    add("multihash(L=4096,P=16,coarser)", MultiHashOptions{4096, 16, MultiHashCellRule::Coarser});
    return sweep;
}

/// Every structure measured, in table order, built on Exec's device: f(variants) for each line.
/// BruteForce is left out: O(n) per query is hours at 1M points on the CPU.
template <class Exec, class F>
void forEachStructure(Exec exec, F&& f) {
    f(defaults<UniformGrid>(exec, "grid"));
    f(defaults<HashGrid>(exec, "hash"));
    f(defaults<KdTree>(exec, "kdtree"));
    f(multiHashSweep(exec));
}

inline bool selected(const std::vector<std::string>& prefixes, const std::string& name) {
    if (prefixes.empty()) return true;
    for (const std::string& p : prefixes)
        if (name.compare(0, p.size(), p) == 0) return true;
    return false;
}

// ---- queries ------------------------------------------------------------------------------------

enum class Query { Within, Knn16, Covering, Segment };

inline const char* queryName(Query q) {
    switch (q) {
        case Query::Within:
            return "within";
        case Query::Knn16:
            return "knn16";
        case Query::Covering:
            return "covering";
        case Query::Segment:
            return "segment";
    }
    return "?";
}

inline std::vector<Query> queriesOf(const BenchSet& s) {
    if (s.spheres()) return {Query::Covering, Query::Segment};
    return {Query::Within, Query::Knn16};
}

/// Per query: how many results and the sum of their indices (written by the kernels), in the
/// memory of Exec's device.
template <class Exec>
struct QueryOutputs {
    Buffer<uint32_t> counts;
    Buffer<uint64_t> indexSums;
    explicit QueryOutputs(size_t n) : counts(Exec::device(), n), indexSums(Exec::device(), n) {}
};

/// The totals over all queries: what every structure must agree on.
struct Totals {
    uint64_t results = 0, indexSum = 0;
    bool operator==(const Totals&) const = default;
};

/// Sums the outputs (copied to the host first when they are on a GPU).
template <class Exec>
Totals totalsOf(const QueryOutputs<Exec>& out) {
    const std::vector<uint32_t> counts = out.counts.toHost();
    const std::vector<uint64_t> sums = out.indexSums.toHost();
    Totals t;
    for (size_t i = 0; i < counts.size(); ++i) {
        t.results += counts[i];
        t.indexSum += sums[i];
    }
    return t;
}

/// The launch names of the query kernels (KernelStats), in the order of Query.
inline constexpr const char* kQueryKernelNames[] = {"bench.within", "bench.knn16",
                                                    "bench.covering", "bench.segment"};

/// The query arrays of a PreparedSet (device pointers) and the segments' common length.
struct QueryArrays {
    const Vec3f* centers;     // ball centres, covered points or segment origins
    const Float* radii;       // points sets: each query's radius
    const Vec3f* directions;  // spheres sets: each segment's unit direction
    Float segmentLength;
};

/// Query i of type kQuery on the view: add(j) for every result j. knn16: a fixed local array of
/// 16 indices.
template <Query kQuery, class View, class Add>
CA_HD void runQuery(const View& view, const QueryArrays& a, size_t i, Add& add) {
    if constexpr (kQuery == Query::Within) {
        view.forEachPointWithin(a.centers[i], a.radii[i], add);
    } else if constexpr (kQuery == Query::Knn16) {
        uint32_t nearest[16], found = 0;
        view.kNearest(a.centers[i], 16, 2 * a.radii[i], nearest, found);
        for (uint32_t k = 0; k < found; ++k) add(nearest[k]);
    } else if constexpr (kQuery == Query::Covering) {
        view.forEachSphereCovering(a.centers[i], add);
    } else {
        view.forEachSphereOnSegment(a.centers[i], a.directions[i], a.segmentLength, add);
    }
}

/// Runs every query of type kQuery on the view (one launch on Exec's device): each query counts
/// its results and sums their indices into `out`.
template <Query kQuery, class Exec, class View>
void launchQueries(Exec exec, const View& view, const QueryArrays& a, size_t n,
                   QueryOutputs<Exec>& out) {
    uint32_t* counts = out.counts.data();
    uint64_t* sums = out.indexSums.data();
    launch(exec, kQueryKernelNames[int(kQuery)], n, [=] CA_HD(size_t i) {
        uint32_t count = 0;
        uint64_t sum = 0;
        auto add = [&](uint32_t j) {
            ++count;
            sum += j;
        };
        runQuery<kQuery>(view, a, i, add);
        counts[i] = count;
        sums[i] = sum;
    });
}

/// Milliseconds of f() on the CPU: the host clock.
template <class F>
double timedMs(CpuExec, F&& f) {
    const auto start = Clock::now();
    f();
    return msSince(start);
}

#if defined(__CUDACC__)
/// Milliseconds of f() on the GPU: CUDA events around it on the default stream (what f launches
/// there, and the host's gaps between the launches), waiting for the end.
template <class F>
double timedMs(GpuExec, F&& f) {
    CudaEvent start, stop;
    CA_CUDA_CHECK(cudaEventRecord(start.get()));
    f();
    CA_CUDA_CHECK(cudaEventRecord(stop.get()));
    CA_CUDA_CHECK(cudaEventSynchronize(stop.get()));
    float ms = 0;
    CA_CUDA_CHECK(cudaEventElapsedTime(&ms, start.get(), stop.get()));
    return double(ms);
}
#endif

/// Untimed runs before the timed ones: none on the CPU; one on the GPU, where the first launch of
/// a kernel loads its module (CUDA's lazy loading) and the first allocations grow the pool.
inline int warmUpRuns(CpuExec) { return 0; }
#if defined(__CUDACC__)
inline int warmUpRuns(GpuExec) { return 1; }
#endif

/// Runs every query of the set of type q on Exec's device; returns the milliseconds.
template <class Exec, class View>
double runQueries(Exec exec, const View& view, Query q, const PreparedSet<Exec>& p,
                  QueryOutputs<Exec>& out) {
    const QueryArrays a{p.queries.data(), p.queryRadii.data(), p.directions.data(),
                        p.set.segmentLength};
    const size_t n = p.queries.size();
    return timedMs(exec, [&] {
        switch (q) {
            case Query::Within:
                return launchQueries<Query::Within>(exec, view, a, n, out);
            case Query::Knn16:
                return launchQueries<Query::Knn16>(exec, view, a, n, out);
            case Query::Covering:
                return launchQueries<Query::Covering>(exec, view, a, n, out);
            case Query::Segment:
                return launchQueries<Query::Segment>(exec, view, a, n, out);
        }
    });
}

// ---- measurement and output ---------------------------------------------------------------------

/// One row of the CSV and the table.
struct Row {
    std::string set, structure, query;
    size_t points = 0, queries = 0;
    double buildMs = 0, bytesPerPoint = 0, queryMs = 0, resultsPerQuery = 0;
    int threads = 0;
    Vec3f extent;
    Float radius = 0, medianRadius = 0;
};

/// The CSV (and the printed table). `device` non-empty adds a last column `device` with it.
class Report {
public:
    explicit Report(const std::string& path, std::string device = "")
        : path_(path), device_(std::move(device)) {
        std::filesystem::create_directories(std::filesystem::path(path).parent_path());
        file_ = std::fopen(path.c_str(), "w");
        if (!file_) throw Error("cannot write " + path);
        std::fprintf(
            file_,
            "set,points,structure,query,build_ms,bytes_per_point,queries,query_ms,queries_per_s,"
            "results_per_query,threads,extent_x,extent_y,extent_z,radius,median_radius%s\n",
            device_.empty() ? "" : ",device");
    }
    ~Report() {
        if (file_) std::fclose(file_);
    }
    Report(const Report&) = delete;
    Report& operator=(const Report&) = delete;

    static void printHeader() {
        std::printf("%-22s %-24s %-9s %9s %7s %9s %10s %10s %9s\n", "set", "structure", "query",
                    "build ms", "B/pt", "queries", "query ms", "Mq/s", "res/q");
    }
    /// Prints the row (the table) and appends it to the CSV at once (a long run keeps its rows).
    void add(const Row& r) {
        const double perSecond = r.queryMs > 0 ? double(r.queries) / (r.queryMs * 1e-3) : 0;
        std::printf("%-22s %-24s %-9s %9.1f %7.2f %9zu %10.1f %10.3f %9.2f\n", r.set.c_str(),
                    r.structure.c_str(), r.query.c_str(), r.buildMs, r.bytesPerPoint, r.queries,
                    r.queryMs, perSecond * 1e-6, r.resultsPerQuery);
        std::fflush(stdout);
        std::fprintf(file_,
                     "%s,%zu,\"%s\",%s,%.3f,%.3f,%zu,%.3f,%.1f,%.4f,%d,%.6g,%.6g,%.6g,%.6g,%.6g",
                     r.set.c_str(), r.points, r.structure.c_str(), r.query.c_str(), r.buildMs,
                     r.bytesPerPoint, r.queries, r.queryMs, perSecond, r.resultsPerQuery, r.threads,
                     double(r.extent.x), double(r.extent.y), double(r.extent.z), double(r.radius),
                     double(r.medianRadius));
        if (!device_.empty()) std::fprintf(file_, ",\"%s\"", device_.c_str());
        std::fprintf(file_, "\n");
        std::fflush(file_);
    }
    const std::string& path() const { return path_; }

private:
    std::string path_, device_;
    std::FILE* file_ = nullptr;
};

/// The totals of the first structure measured for each (set, query), and every disagreement.
class AgreementCheck {
public:
    void check(const std::string& set, Query q, const std::string& structure, const Totals& t) {
        const std::string key = set + " " + queryName(q);
        auto [it, first] = reference_.try_emplace(key, structure, t);
        if (first || it->second.second == t) return;
        disagree(key, structure, t, it->second, "the structures disagree");
    }
    /// Compares t (of `structure`, measured apart from the others: on the other device) with the
    /// reference of (set, q), tolerating up to `allowedResults` differing results (and index
    /// sums apart by that many indices below `points`); prints the outcome. A larger difference
    /// is a disagreement. Without a reference (no structure measured) it does nothing.
    void checkNear(const std::string& set, Query q, const std::string& structure, const Totals& t,
                   uint64_t allowedResults, uint64_t points) {
        const std::string key = set + " " + queryName(q);
        const auto it = reference_.find(key);
        if (it == reference_.end()) return;
        const Totals& ref = it->second.second;
        const uint64_t results = absDiff(t.results, ref.results);
        const uint64_t indexSum = absDiff(t.indexSum, ref.indexSum);
        if (results > allowedResults || indexSum > allowedResults * points) {
            disagree(key, structure, t, it->second, "beyond the tolerated rounding");
            return;
        }
        const char* refName = it->second.first.c_str();
        if (results == 0 && indexSum == 0)
            std::printf("%s: %s (%llu results) returns the same totals as %s\n", key.c_str(),
                        structure.c_str(), (unsigned long long)t.results, refName);
        else
            std::printf(
                "%s: %s (%llu results) differs from %s by %llu result(s) and %llu in the index "
                "sum: rounding (up to %llu results tolerated)\n",
                key.c_str(), structure.c_str(), (unsigned long long)t.results, refName,
                (unsigned long long)results, (unsigned long long)indexSum,
                (unsigned long long)allowedResults);
    }
    int failures() const { return failures_; }

    /// The end of a run: "all structures agree" (true) or the count of disagreements (false).
    bool summarize() const {
        if (failures_ > 0) {
            std::printf("!!!!! ERROR: %d disagreement(s) between structures (see above) !!!!!\n",
                        failures_);
            return false;
        }
        std::printf(
            "all structures agree (result counts and index sums of every set and query)\n");
        return true;
    }

private:
    using Reference = std::pair<std::string, Totals>;  // the first structure measured, its totals

    static uint64_t absDiff(uint64_t a, uint64_t b) { return a > b ? a - b : b - a; }
    void disagree(const std::string& key, const std::string& structure, const Totals& t,
                  const Reference& reference, const char* verdict) {
        const auto& [refName, ref] = reference;
        std::printf(
            "\n!!!!! ERROR: %s: %s returned %llu results (index sum %llu), %s returned %llu (index "
            "sum %llu): %s !!!!!\n\n",
            key.c_str(), structure.c_str(), (unsigned long long)t.results,
            (unsigned long long)t.indexSum, refName.c_str(), (unsigned long long)ref.results,
            (unsigned long long)ref.indexSum, verdict);
        ++failures_;
    }

    std::map<std::string, Reference> reference_;
    int failures_ = 0;
};

struct Context {
    const Options& options;
    int threads;  // the rows' `threads` column
    Report& report;
    AgreementCheck& agreement;
};

/// Builds variant v --repeat times (best time), then runs each query type --repeat times (best
/// time) and reports a row per query type, after warmUpRuns(exec) untimed runs of each. Every
/// run's totals go to the agreement check: a structure's results depend on its build only, so
/// its repeats must agree as well.
template <class Exec, class S>
void measure(Exec exec, const Variant<S>& v, const PreparedSet<Exec>& p, Context& c) {
    const BenchSet& s = p.set;
    const int warmUp = warmUpRuns(exec);
    const int runs = warmUp + c.options.repeat;
    std::optional<S> structure;
    double buildMs = 1e300;
    for (int r = 0; r < runs; ++r) {
        structure.reset();  // one structure in memory at a time
        const double ms = timedMs(exec, [&] { structure.emplace(v.build(p.points())); });
        if (r >= warmUp) buildMs = std::min(buildMs, ms);
    }
    const auto view = structure->view();
    for (Query q : queriesOf(s)) {
        QueryOutputs<Exec> out(s.queries.size());
        double queryMs = 1e300;
        Totals totals;
        for (int r = 0; r < runs; ++r) {
            const double ms = runQueries(exec, view, q, p, out);
            if (r >= warmUp) queryMs = std::min(queryMs, ms);
            totals = totalsOf(out);
            c.agreement.check(s.name, q, v.name, totals);
        }
        Row row;
        row.set = s.name;
        row.structure = v.name;
        row.query = queryName(q);
        row.points = s.positions.size();
        row.queries = s.queries.size();
        row.buildMs = buildMs;
        row.bytesPerPoint =
            double(structure->memoryBytes()) / double(std::max<size_t>(1, row.points));
        row.queryMs = queryMs;
        row.resultsPerQuery = double(totals.results) / double(std::max<size_t>(1, row.queries));
        row.threads = c.threads;
        row.extent = p.extent;
        row.radius = p.radius;
        row.medianRadius = p.medianRadius;
        c.report.add(row);
    }
}

template <class Exec>
void printSetStatistics(const PreparedSet<Exec>& p) {
    const BenchSet& s = p.set;
    std::printf("\n%s: %zu %s, box extent %.4g x %.4g x %.4g, ", s.name.c_str(), s.positions.size(),
                s.spheres() ? "spheres" : "points", double(p.extent.x), double(p.extent.y),
                double(p.extent.z));
    if (s.spheres())
        std::printf("radius median %.4g, largest %.4g; %zu queries, segments of length %.4g\n",
                    double(p.medianRadius), double(p.radius), s.queries.size(),
                    double(s.segmentLength));
    else
        std::printf("common radius %.4g; %zu queries, query radius median %.4g\n", double(p.radius),
                    s.queries.size(), double(p.medianRadius));
}

/// Every selected structure on one point set, on Exec's device.
template <class Exec>
void measureSet(Exec exec, const BenchSet& s, Context& c) {
    const PreparedSet<Exec> prepared(s);
    printSetStatistics(prepared);
    Report::printHeader();
    forEachStructure(exec, [&](const auto& variants) {
        for (const auto& v : variants)
            if (selected(c.options.structures, v.name)) measure(exec, v, prepared, c);
    });
}

/// A program's run: opens the CSV (default todaysCsv; `device`: Report's last column), prints
/// `heading`, calls measureSet(set, context) for every selected set, then prints where the CSV
/// went and the agreement's verdict. Returns the exit status: 0, or 1 after a disagreement or an
/// error (printed). `threads`: the rows' threads column.
template <class MeasureSet>
int runBench(const Program& program, const Options& o, int threads, const std::string& device,
             const std::string& heading, MeasureSet&& measureSet) {
    try {
        Report report(o.csv.empty() ? todaysCsv(program) : o.csv, device);
        AgreementCheck agreement;
        Context context{o, threads, report, agreement};
        std::printf("%s\n", heading.c_str());
        const auto start = Clock::now();
        forEachSet(o, [&](const BenchSet& s) { measureSet(s, context); });
        std::printf("\nwrote %s (%.0f s)\n", report.path().c_str(), msSince(start) * 1e-3);
        return agreement.summarize() ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", program.name, e.what());
        return 1;
    }
}

}  // namespace caustica::spatial_bench
