// sppm_visible_bsdf_test.cpp — SppmVisibleBsdf (the gather's BSDF resolved once per visible
// point) gives evalBsdf's value bit for bit, for plain, twosided, textured, bump- and
// normal-mapped leaves (its own path) and blends (evalBsdf's), from both sides.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "caustica/integrators/sppm/sppm_visible_bsdf.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"
#include "scene/bsdf_test_util.h"

namespace caustica {
namespace {

struct Case {
    std::string name;
    std::vector<Bsdf> bsdfs;
    uint32_t id = 0;
};

std::vector<Case> cases() {
    std::vector<Case> c;
    c.push_back({"diffuse", {test::diffuse(Spectrum(0.6f, 0.5f, 0.4f))}, 0});
    c.push_back({"plastic", {test::plastic()}, 0});
    c.push_back({"roughconductor", {test::roughConductor(0.3f, 0.1f)}, 0});
    Case two{"twosided diffuse / roughconductor", {}, 0};
    two.id = test::addTwoSided(two.bsdfs, test::diffuse(Spectrum(0.7f)), test::roughConductor(0.2f, 0.2f));
    c.push_back(two);
    Bsdf textured = test::diffuse(Spectrum(0.5f));
    textured.numTextures = 1;
    textured.textures[0] = BsdfTexture{BsdfParam::Reflectance, 0};
    c.push_back({"textured diffuse", {textured}, 0});
    c.push_back({"bumpmap", {test::diffuse(Spectrum(0.7f)), test::frameAdapter(BsdfType::BumpMap, 0, 0, 3)}, 1});
    c.push_back({"normalmap", {test::roughConductor(0.2f, 0.2f), test::frameAdapter(BsdfType::NormalMap, 0, 1)}, 1});
    Bsdf blend;
    blend.type = BsdfType::Blend;
    blend.front = 0;
    blend.back = 1;
    blend.weight = 0.3f;
    c.push_back({"blend (two leaves)", {test::diffuse(Spectrum(0.7f)), test::roughConductor(0.2f, 0.2f), blend}, 2});
    return c;
}

uint32_t bitsOf(Float v) { return std::bit_cast<uint32_t>(v); }

TEST(SppmVisibleBsdf, EqualsEvalBsdfBitForBit) {
    // A height field and a tilted normal map as textures 0 and 1 (bitmaps).
    std::vector<Texture> textures(2);
    std::vector<Spectrum> texels;
    textures[0].type = TextureType::Bitmap;
    textures[0].width = textures[0].height = 4;
    for (int i = 0; i < 16; ++i) texels.push_back(Spectrum(Float((i * 7) % 5) * 0.05f + 0.1f));
    textures[1].type = TextureType::Bitmap;
    textures[1].width = textures[1].height = 2;
    textures[1].texelOffset = 16;
    const Vec3f n = normalize(Vec3f(0.4f, -0.3f, 1));
    for (int i = 0; i < 4; ++i) texels.push_back(Spectrum((n.x + 1) / 2, (n.y + 1) / 2, (n.z + 1) / 2));

    IndependentSampler sampler(7, 0, 21);
    for (const Case& c : cases()) {
        const Span<const Bsdf> bsdfs(c.bsdfs);
        int nonzero = 0;
        for (int point = 0; point < 200; ++point) {
            SppmVisiblePoint vp;
            vp.si = test::surfaceAt(sampleUniformSphere(sampler.get2D()));
            vp.si.ng = normalize(vp.si.ns + sampleUniformSphere(sampler.get2D()) * 0.2f);
            if (dot(vp.si.ng, vp.si.ns) < 0) vp.si.ng = -vp.si.ng;
            vp.si.dpdu = cross(vp.si.ns, sampleUniformSphere(sampler.get2D()));
            vp.si.dpdv = cross(vp.si.ns, vp.si.dpdu);
            vp.si.uv = sampler.get2D();
            vp.si.textures = {textures, texels};
            vp.wo = sampleUniformSphere(sampler.get2D());  // front and back
            vp.bsdf = c.id;
            const SppmVisibleBsdf resolved(bsdfs, vp);
            for (int k = 0; k < 50; ++k) {
                const Vec3f wi = sampleUniformSphere(sampler.get2D());
                const Spectrum want = evalBsdf(bsdfs, c.id, vp.si, vp.wo, wi);
                const Spectrum got = resolved.eval(wi);
                ASSERT_EQ(bitsOf(got.r), bitsOf(want.r)) << c.name;
                ASSERT_EQ(bitsOf(got.g), bitsOf(want.g)) << c.name;
                ASSERT_EQ(bitsOf(got.b), bitsOf(want.b)) << c.name;
                nonzero += want.isBlack() ? 0 : 1;
            }
        }
        EXPECT_GT(nonzero, 1000) << c.name << ": too few directions with a value to compare";
    }
}

}  // namespace
}  // namespace caustica
