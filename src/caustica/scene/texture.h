// texture.h — Mitsuba 3's textures as one tagged record, evaluated at a surface's uv in kernels.
//
// API (for BSDF code and loaders):
// - `Texture` (constant / bitmap / checkerboard); the scene owns them in `Scene::textures` and
//   the bitmap texels in `Scene::texels` (linear RGB, row 0 = the image's top row, as Mitsuba
//   reads v = 0 at the top); kernels see them through a `TextureView` (SceneView::textureView(),
//   copied into every SurfaceInteraction as `si.textures`).
// - `evalTexture(view, id, uv)` -> Spectrum (Mitsuba's Texture::eval), `evalTexture1` -> Float
//   (eval_1: the luminance of the colour), `evalTextureGrad` -> d(eval_1)/d(u, v) (eval_1_grad;
//   bilinear bitmaps only, zero otherwise).
// - A BSDF parameter that may be textured is a plain field of `Bsdf` (the constant) plus an
//   entry in `Bsdf::textures` naming the field (`BsdfParam`) and the texture; bsdf.h replaces
//   the field by the texture's value at si.uv before evaluating the BSDF (`applyBsdfTextures`),
//   so BSDF code only ever reads the plain fields. Loaders: `readSpectrumParam` /
//   `readFloatParam` in io/mitsuba/build_textures.h. A new textured field = one `BsdfParam`
//   value and one case in applyBsdfTextures.
// - A checkerboard's colours may be textures themselves (`child0` / `child1`); they are
//   evaluated at the original uv (Mitsuba passes the unchanged interaction down), so nesting is
//   a loop, not recursion. Children always have smaller ids than their parent (built first).
// Evaluation is deterministic and cheap: no allocation, at most four texel fetches.
#pragma once

#include <cstdint>

#include "caustica/util/math.h"
#include "caustica/util/span.h"
#include "caustica/util/spectrum.h"

namespace caustica {

constexpr uint32_t kNoTexture = 0xffffffffu;

enum class TextureType : uint32_t {
    Constant,      // Mitsuba's srgb/uniform/rawconstant: one value everywhere
    Bitmap,        // Mitsuba's bitmap: texels with bilinear or nearest lookup
    Checkerboard,  // Mitsuba's checkerboard: color0 where frac(u) > .5 equals frac(v) > .5
};

enum class TextureFilter : uint32_t { Bilinear, Nearest };
enum class TextureWrap : uint32_t { Repeat, Mirror, Clamp };

/// One texture. `toUv` is Mitsuba's `to_uv` (its 2D affine part, row-major 2x3): uv' = M (u, v, 1).
struct Texture {
    TextureType type = TextureType::Constant;
    Spectrum value{0.0f};      // constant value; checkerboard color0
    Spectrum value1{0.0f};     // checkerboard color1
    // checkerboard: color0 / color1 given as textures (else kNoTexture and value / value1)
    uint32_t child0 = kNoTexture, child1 = kNoTexture;
    uint32_t texelOffset = 0;  // bitmap: first texel in Scene::texels
    int32_t width = 0, height = 0;
    TextureFilter filter = TextureFilter::Bilinear;
    TextureWrap wrap = TextureWrap::Repeat;
    Float toUv[6] = {1, 0, 0, 0, 1, 0};
    Float mean = 0;  // Mitsuba's Texture::mean() (luminance mean for bitmaps); host-side use
};

/// The textures and texels kernels read (device spans on the GPU).
struct TextureView {
    Span<const Texture> textures;
    Span<const Spectrum> texels;
};

namespace texture_detail {

CA_HD_INLINE Vec2f applyToUv(const Texture& t, Vec2f uv) {
    return {t.toUv[0] * uv.x + t.toUv[1] * uv.y + t.toUv[2],
            t.toUv[3] * uv.x + t.toUv[4] * uv.y + t.toUv[5]};
}

/// Dr.Jit's Texture::wrap for an integer texel coordinate (drjit/texture.h): repeat, mirror
/// (flipped every other repetition) or clamp to [0, res).
CA_HD_INLINE int32_t wrapIndex(int32_t pos, int32_t res, TextureWrap wrap) {
    if (wrap == TextureWrap::Clamp) return pos < 0 ? 0 : (pos >= res ? res - 1 : pos);
    const int32_t div = (pos < 0 ? pos + 1 : pos) / res;  // truncating, as Dr.Jit's divisor
    int32_t mod = pos - div * res;
    if (mod < 0) mod += res;
    if (wrap == TextureWrap::Mirror && (((div & 1) == 0) == (pos < 0))) mod = res - 1 - mod;
    return mod;
}

/// Float -> int32 floor that stays defined for huge or non-finite uv (clamped to ±2^30).
CA_HD_INLINE int32_t floorToInt(Float x) {
    const Float f = std::floor(x);
    if (!(f > Float(-1073741824))) return -1073741824;  // also NaN
    if (f > Float(1073741824)) return 1073741824;
    return int32_t(f);
}

CA_HD_INLINE Spectrum texel(const TextureView& v, const Texture& t, int32_t x, int32_t y) {
    x = wrapIndex(x, t.width, t.wrap);
    y = wrapIndex(y, t.height, t.wrap);
    return v.texels[t.texelOffset + uint32_t(y) * uint32_t(t.width) + uint32_t(x)];
}

/// The four texels of a bilinear lookup and the weights of the upper ones (Dr.Jit's
/// eval_fetch: position uv·res − 0.5).
struct BilinearFetch {
    Spectrum f00, f10, f01, f11;
    Float wx, wy;
};

CA_HD_INLINE BilinearFetch fetchBilinear(const TextureView& v, const Texture& t, Vec2f uv) {
    const Float px = uv.x * Float(t.width) - Float(0.5), py = uv.y * Float(t.height) - Float(0.5);
    const int32_t x = floorToInt(px), y = floorToInt(py);
    BilinearFetch f;
    f.wx = px - Float(x);
    f.wy = py - Float(y);
    if (!(f.wx >= 0 && f.wx <= 1)) f.wx = 0;  // non-finite or huge uv: stay defined
    if (!(f.wy >= 0 && f.wy <= 1)) f.wy = 0;
    f.f00 = texel(v, t, x, y);
    f.f10 = texel(v, t, x + 1, y);
    f.f01 = texel(v, t, x, y + 1);
    f.f11 = texel(v, t, x + 1, y + 1);
    return f;
}

/// Mitsuba's checkerboard cell test: true where color0 applies (frac(u) > .5 equals frac(v) > .5).
CA_HD_INLINE bool checkerColor0(const Texture& t, Vec2f uvIn) {
    const Vec2f uv = applyToUv(t, uvIn);
    return (uv.x - std::floor(uv.x) > Float(0.5)) == (uv.y - std::floor(uv.y) > Float(0.5));
}

/// Mitsuba's bitmap eval: the nearest texel or the bilinear interpolation at to_uv(uv).
CA_HD_INLINE Spectrum evalBitmap(const TextureView& v, const Texture& t, Vec2f uvIn) {
    const Vec2f uv = applyToUv(t, uvIn);
    if (t.filter == TextureFilter::Nearest)
        return texel(v, t, floorToInt(uv.x * Float(t.width)), floorToInt(uv.y * Float(t.height)));
    const BilinearFetch f = fetchBilinear(v, t, uv);
    const Spectrum f0 = f.f00 * (1 - f.wx) + f.f10 * f.wx;
    const Spectrum f1 = f.f01 * (1 - f.wx) + f.f11 * f.wx;
    return f0 * (1 - f.wy) + f1 * f.wy;
}

}  // namespace texture_detail

/// Mitsuba's Texture::eval at uv.
CA_HD_INLINE Spectrum evalTexture(const TextureView& v, uint32_t id, Vec2f uv) {
    using namespace texture_detail;
    for (;;) {  // descends through nested checkerboards (child ids decrease: terminates)
        const Texture& t = v.textures[id];
        switch (t.type) {
            case TextureType::Constant:
                return t.value;
            case TextureType::Bitmap:
                return evalBitmap(v, t, uv);
            case TextureType::Checkerboard: {
                const bool c0 = checkerColor0(t, uv);
                const uint32_t child = c0 ? t.child0 : t.child1;
                if (child == kNoTexture) return c0 ? t.value : t.value1;
                id = child;
                break;
            }
            default:
                return {};
        }
    }
}

/// Mitsuba 3.9.1's Texture::eval_1: a bitmap's (or rawconstant's) luminance; a colour value's
/// mean (Mitsuba's srgb texture); a checkerboard's eval_1 takes color0 where eval takes color1
/// and vice versa (its eval_1 tests `mask.x != mask.y`; checked with Mitsuba's Python bindings).
CA_HD_INLINE Float evalTexture1(const TextureView& v, uint32_t id, Vec2f uv) {
    using namespace texture_detail;
    for (;;) {
        const Texture& t = v.textures[id];
        switch (t.type) {
            case TextureType::Constant:
                return t.value.luminance();
            case TextureType::Bitmap:
                return evalBitmap(v, t, uv).luminance();
            case TextureType::Checkerboard: {
                const bool c0 = !checkerColor0(t, uv);
                const uint32_t child = c0 ? t.child0 : t.child1;
                if (child == kNoTexture) return (c0 ? t.value : t.value1).average();
                id = child;
                break;
            }
            default:
                return 0;
        }
    }
}

/// Mitsuba's bitmap eval_1_grad: the gradient of the bilinearly interpolated luminance with
/// respect to (u, v), through to_uv. Zero for nearest filtering and for other textures (the
/// loader refuses those where a gradient is needed).
CA_HD_INLINE Vec2f evalTextureGrad(const TextureView& v, uint32_t id, Vec2f uvIn) {
    using namespace texture_detail;
    const Texture& t = v.textures[id];
    if (t.type != TextureType::Bitmap || t.filter != TextureFilter::Bilinear) return {0, 0};
    const BilinearFetch f = fetchBilinear(v, t, applyToUv(t, uvIn));
    const Float l00 = f.f00.luminance(), l10 = f.f10.luminance();
    const Float l01 = f.f01.luminance(), l11 = f.f11.luminance();
    // Partials with respect to the pixel coordinates, then through to_uv (transpose multiply).
    const Float dx = (1 - f.wy) * (l10 - l00) + f.wy * (l11 - l01);
    const Float dy = (1 - f.wx) * (l01 - l00) + f.wx * (l11 - l10);
    const Float du = t.toUv[0] * dx + t.toUv[3] * dy;
    const Float dv = t.toUv[1] * dx + t.toUv[4] * dy;
    return {Float(t.width) * du, Float(t.height) * dv};
}

}  // namespace caustica
