// build_film.cpp — Mitsuba films, reconstruction filters and samplers -> FilmDesc, the camera's
// crop window, Scene::sampleCount and Scene::seed.
//
// | plugin    | parameters (default)                                                        |
// |-----------|-----------------------------------------------------------------------------|
// | hdrfilm   | width (768), height (576), crop_offset_x/y (0), crop_width/height (width,  |
// |           | height; the window must fit in the film), rfilter (gaussian);              |
// |           | pixel_format, component_format, file_format ignored                        |
// | ldrfilm   | as hdrfilm, plus tonemap_method (gamma | reinhard), gamma (-1 = sRGB),      |
// |           | exposure (0), key (0.18), burn (0); file_format png; pixel_format ignored   |
// | box/tent/gaussian rfilter | tent: radius (1); gaussian: stddev (0.5), radius 4 stddev    |
// | independent, stratified, multijitter, orthogonal, ldsampler | sample_count (4), seed (0) |
//
// caustica always samples independently with its counter-based generator: the other samplers'
// sample counts are rounded exactly as Mitsuba 3 rounds them (so that a scene renders the same
// number of samples per pixel), their patterns are not reproduced (same expected image, other
// noise).
#include "caustica/io/mitsuba/build_film.h"

#include <cmath>

#include "caustica/io/mitsuba/plugin_table.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

namespace {

/// At most one child of `category`; -1 when there is none.
int singleChild(Params& p, const std::string& category) {
    std::vector<int> c = p.takeChildren(category);
    if (c.size() > 1) p.failAtChild(c[1], "takes at most one <" + category + ">");
    return c.empty() ? -1 : c[0];
}

FilterDesc boxFilter(Params&) {
    return {FilterType::Box, 0.5f, 0.5f};
}

FilterDesc tentFilter(Params& p) {
    Float r = p.getFloat("radius", 1.0f);
    if (!(r > 0)) p.fail(*p.find("radius"), "must be positive");
    return {FilterType::Tent, r, 0.5f};
}

FilterDesc gaussianFilter(Params& p) {
    Float s = p.getFloat("stddev", 0.5f);
    if (!(s > 0)) p.fail(*p.find("stddev"), "must be positive");
    return {FilterType::Gaussian, 4 * s, s};
}

using FilterFn = FilterDesc (*)(Params&);
const PluginTable<FilterFn> kFilterPlugins{
    {{"box", boxFilter}, {"gaussian", gaussianFilter}, {"tent", tentFilter}}};

/// A non-negative integer parameter.
int getCount(Params& p, const char* name, int def) {
    const int v = p.getInt(name, def);
    if (v < 0) p.fail(*p.find(name), "must not be negative");
    return v;
}

/// Mitsuba 3's Film: size, crop window (it must lie inside the film) and rfilter.
FilmDesc commonFilm(BuildContext& ctx, Params& p, Camera& camera) {
    FilmDesc film;
    const int w = p.getInt("width", 768), h = p.getInt("height", 576);
    if (w <= 0 || h <= 0 || w > 32768 || h > 32768 || int64_t(w) * h > (int64_t(1) << 28))
        p.fail("absurd resolution " + std::to_string(w) + "x" + std::to_string(h) +
               " (each side 1..32768, at most 2^28 pixels)");
    const int cx = getCount(p, "crop_offset_x", 0), cy = getCount(p, "crop_offset_y", 0);
    const int cw = getCount(p, "crop_width", w), ch = getCount(p, "crop_height", h);
    if (cw == 0 || ch == 0 || int64_t(cx) + cw > w || int64_t(cy) + ch > h)
        p.fail("crop window " + std::to_string(cw) + "x" + std::to_string(ch) + " at (" +
               std::to_string(cx) + ", " + std::to_string(cy) + ") does not fit in the " +
               std::to_string(w) + "x" + std::to_string(h) + " film");
    film.width = cw;
    film.height = ch;
    camera.width = w;
    camera.height = h;
    camera.cropX = cx;
    camera.cropY = cy;
    int rfilter = singleChild(p, "rfilter");
    if (rfilter >= 0) {
        ctx.used.insert(rfilter);
        Params fp(ctx.desc, rfilter);
        film.filter = kFilterPlugins.find(fp)(fp);
        fp.finish(ctx.warnings);
    }
    return film;
}

FilmDesc hdrFilm(BuildContext& ctx, Params& p, Camera& camera) {
    FilmDesc film = commonFilm(ctx, p, camera);
    for (const char* ignored : {"pixel_format", "component_format", "file_format"})
        p.ignore(ignored, ctx.warnings);
    return film;
}

/// Mitsuba 0.6's ldrfilm (Mitsuba 3 has no LDR film): PNG output tonemapped (film/tonemap.h).
FilmDesc ldrFilm(BuildContext& ctx, Params& p, Camera& camera) {
    FilmDesc film = commonFilm(ctx, p, camera);
    ToneMapDesc& t = film.tonemap;
    t.ldr = true;
    const std::string method = p.getString("tonemap_method", "gamma");
    if (method == "gamma")
        t.method = ToneMapMethod::Gamma;
    else if (method == "reinhard")
        t.method = ToneMapMethod::Reinhard;
    else
        p.fail(*p.find("tonemap_method"), "must be gamma or reinhard, not '" + method + "'");
    t.gamma = p.getFloat("gamma", -1.0f);
    if (!(t.gamma > 0 || t.gamma == -1)) p.fail(*p.find("gamma"), "must be positive or -1 (sRGB)");
    t.exposure = p.getFloat("exposure", 0.0f);
    if (!(std::fabs(t.exposure) <= 64)) p.fail(*p.find("exposure"), "must be within [-64, 64]");
    t.key = p.getFloat("key", 0.18f);
    if (!(t.key > 0)) p.fail(*p.find("key"), "must be positive");
    t.burn = p.getFloat("burn", 0.0f);
    if (!(t.burn >= 0 && t.burn <= 1)) p.fail(*p.find("burn"), "must be between 0 and 1");
    const std::string format = p.getString("file_format", "png");
    if (format != "png") p.fail(*p.find("file_format"), "only 'png' is supported");
    for (const char* ignored : {"pixel_format", "banner", "high_quality_edges"})
        p.ignore(ignored, ctx.warnings);
    return film;
}

using FilmFn = FilmDesc (*)(BuildContext&, Params&, Camera&);
const PluginTable<FilmFn> kFilmPlugins{
    {{"hdrfilm", hdrFilm}, {"ldrfilm", ldrFilm}},
    {{"specfilm", "spectral rendering is not supported"}}};

// ---- samplers: Mitsuba 3.9's sample-count rounding per type --------------------------------

int64_t isqrtCeil(int64_t n) {
    int64_t r = int64_t(std::sqrt(double(n)));
    while (r * r < n) ++r;
    while (r > 1 && (r - 1) * (r - 1) >= n) --r;
    return r;
}

bool isPrime(int64_t n) {
    if (n < 2) return false;
    for (int64_t d = 2; d * d <= n; ++d)
        if (n % d == 0) return false;
    return true;
}

int64_t keepCount(int64_t n) { return n; }
/// stratified: the next square.
int64_t squareCount(int64_t n) {
    const int64_t r = isqrtCeil(n);
    return r * r;
}
/// multijitter: floor(√n) columns and as many rows as needed.
int64_t multijitterCount(int64_t n) {
    int64_t x = isqrtCeil(n);
    if (x * x > n) --x;
    x = std::max<int64_t>(x, 1);
    return x * ((n + x - 1) / x);
}
/// orthogonal: the square of the next prime.
int64_t primeSquareCount(int64_t n) {
    int64_t p = std::max<int64_t>(2, isqrtCeil(n));
    while (!isPrime(p)) ++p;
    return p * p;
}
/// ldsampler: the square of the next power of two (at least 4).
int64_t powerOfFourCount(int64_t n) {
    int64_t r = 2;
    while (r * r < n) r *= 2;
    return r * r;
}

using CountFn = int64_t (*)(int64_t);
const PluginTable<CountFn> kSamplerPlugins{{{"independent", keepCount},
                                            {"stratified", squareCount},
                                            {"multijitter", multijitterCount},
                                            {"orthogonal", primeSquareCount},
                                            {"ldsampler", powerOfFourCount}}};

}  // namespace

FilmDesc buildFilm(BuildContext& ctx, int object, Camera& camera) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    FilmDesc film = kFilmPlugins.find(p)(ctx, p, camera);
    p.finish(ctx.warnings);
    return film;
}

void buildSampler(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    const CountFn round = kSamplerPlugins.find(p);
    const int count = p.getInt("sample_count", 4);
    if (count <= 0) p.fail(*p.find("sample_count"), "must be positive");
    const int seed = p.getInt("seed", 0);
    if (seed < 0) p.fail(*p.find("seed"), "must not be negative");
    if (p.object().type != "independent" && p.object().type != "ldsampler" &&
        !p.getBool("jitter", true))
        p.fail(*p.find("jitter"), "must be true (caustica samples independently, never on a grid)");
    const int64_t rounded = round(count);
    if (rounded > (int64_t(1) << 24))
        p.fail(*p.find("sample_count"), "is too large (at most 2^24 after rounding)");
    if (rounded != count) {
        const Property* at = p.find("sample_count");
        ctx.warnings.push_back(at->where.file + ":" + std::to_string(at->where.line) + ": " +
                               p.object().describe() + ": sample_count " + std::to_string(count) +
                               " rounded to " + std::to_string(rounded) + " (as Mitsuba 3)");
    }
    ctx.scene.sampleCount = int(rounded);
    ctx.scene.seed = uint64_t(seed);
    p.finish(ctx.warnings);
}

}  // namespace caustica::mitsuba
