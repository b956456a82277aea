// bsdf_frame_chi2_test.cpp — BSDFs in the dp/du shading frame: χ² tests of anisotropic microfacet
// sampling (roughconductor, roughdielectric) with a surface frame that is not the normal's default
// one, of bumpmap / normalmap (perturbed frames, Mitsuba's side tests) and of twosided around them;
// per-sample weight == eval/pdf; and the orientation of anisotropic lobes along dp/du.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"
#include "scene/bsdf_test_util.h"
#include "scene/chi2.h"

namespace caustica {
namespace {

/// A 4 x 4 height field (raw luminance) for the bump and normal map cases.
struct FrameTextures {
    std::vector<Texture> textures;
    std::vector<Spectrum> texels;
    FrameTextures() {
        Texture height;
        height.type = TextureType::Bitmap;
        height.width = height.height = 4;
        textures.push_back(height);
        for (int i = 0; i < 16; ++i) texels.push_back(Spectrum(Float((i * 7) % 5) * 0.05f));
        Texture normals;  // a constant tilted tangent-space normal, as a 2 x 2 bitmap
        normals.type = TextureType::Bitmap;
        normals.width = normals.height = 2;
        normals.texelOffset = 16;
        textures.push_back(normals);
        const Vec3f n = normalize(Vec3f(0.4f, -0.3f, 1));
        for (int i = 0; i < 4; ++i)
            texels.push_back(Spectrum((n.x + 1) / 2, (n.y + 1) / 2, (n.z + 1) / 2));
    }
};

struct FrameCase {
    std::string name;
    std::vector<Bsdf> bsdfs;
    uint32_t id = 0;
    double thetaO = 40, phiO = 30;  // wo in the frame of ns
    bool back = false;              // view from below the surface
    int nTheta = 64, nPhi = 128;    // histogram resolution (finer for narrow lobes)
};

SurfaceInteraction tiltedSurface(const FrameTextures& tex) {
    SurfaceInteraction si = test::surfaceAt(normalize(Vec3f(0.2f, -0.3f, 1)));
    si.ng = normalize(Vec3f(0.1f, -0.2f, 1));
    si.dpdu = Vec3f(1.0f, 2.0f, 0.3f);  // not the normal's default frame
    si.dpdv = cross(si.ns, si.dpdu) * 0.7f;
    si.uv = Vec2f(0.37f, 0.61f);
    si.textures = {tex.textures, tex.texels};
    return si;
}

void runFrameChi2(const FrameCase& c, uint64_t seed) {
    const FrameTextures tex;
    const Span<const Bsdf> bsdfs(c.bsdfs);
    const SurfaceInteraction si = tiltedSurface(tex);
    Frame frame(si.ns);
    Vec3f wo = test::directionDeg(frame, c.thetaO, c.phiO);
    if (c.back) wo = wo - si.ns * (2 * dot(wo, si.ns));
    test::SphereGrid grid;
    grid.frame = frame;
    grid.nTheta = c.nTheta;
    grid.nPhi = c.nPhi;
    // Per-sample consistency: no gross disagreement (1%); float rounding in the half vector that
    // eval/pdf rebuild from (wo, wi) of near-grazing refractions leaves a few samples of a
    // million 0.1% apart, so at most 2e-5 of them may miss the 0.1% tolerance.
    int bad = 0, gross = 0;
    std::string firstBad;
    auto keep = [&](const BsdfSample& bs) {
        const Spectrum f = evalBsdf(bsdfs, c.id, si, wo, bs.wi);
        const Float pdf = pdfBsdf(bsdfs, c.id, si, wo, bs.wi);
        if (!test::relClose(bs.pdf, pdf, 1e-2) || !(pdf > 0) ||
            !test::relClose(bs.weight.g, f.g / pdf, 1e-2))
            ++gross;
        if (!test::relClose(bs.pdf, pdf) || !(pdf > 0) ||
            !test::relClose(bs.weight.g, f.g / pdf)) {
            if (bad++ == 0)
                firstBad = "pdf " + std::to_string(bs.pdf) + " vs " + std::to_string(pdf) +
                           ", weight " + std::to_string(bs.weight.g) + " vs " +
                           std::to_string(f.g / pdf);
        }
        return true;
    };
    const test::Chi2Result r = test::bsdfChi2(bsdfs, bsdfs, c.id, si, wo, grid, seed, 4, keep);
    EXPECT_TRUE(r.passed()) << c.name << ": " << r.describe();
    test::printChi2IfVerbose(c.name, r);
    EXPECT_EQ(gross, 0) << c.name << ": " << firstBad;
    EXPECT_LE(bad, test::kBsdfChi2Samples / 50000) << c.name << ": " << firstBad;
}

Bsdf twoSided(uint32_t front, uint32_t back) {
    Bsdf b;
    b.type = BsdfType::TwoSided;
    b.front = front;
    b.back = back;
    return b;
}

std::vector<FrameCase> makeCases() {
    std::vector<FrameCase> cases;
    for (MicrofacetType type : {MicrofacetType::Beckmann, MicrofacetType::GGX}) {
        const std::string d = type == MicrofacetType::GGX ? "ggx" : "beckmann";
        for (double t : {20.0, 70.0}) {
            Bsdf b = test::roughConductor(0.08f, 0.45f);
            b.distribution = type;
            cases.push_back({"roughconductor_aniso_" + d + "_" + std::to_string(int(t)), {b}, 0,
                             t, 30, false, 128, 256});
        }
        cases.push_back({"roughdielectric_aniso_" + d,
                         {test::roughDielectric(1.5f, 0.1f, 0.4f, type)}, 0, 50, 120, false, 128,
                         256});
        cases.push_back({"roughdielectric_aniso_inside_" + d,
                         {test::roughDielectric(1.5f, 0.1f, 0.4f, type)}, 0, 30, 200, true, 128,
                         256});
    }
    cases.push_back({"bumpmap_diffuse",
                     {test::diffuse(Spectrum(0.7f)), test::frameAdapter(BsdfType::BumpMap, 0, 0, 3)}, 1, 60,
                     10});
    cases.push_back({"bumpmap_roughconductor",
                     {test::roughConductor(0.2f, 0.2f), test::frameAdapter(BsdfType::BumpMap, 0, 0, 2)}, 1, 30,
                     80});
    cases.push_back({"normalmap_diffuse",
                     {test::diffuse(Spectrum(0.7f)), test::frameAdapter(BsdfType::NormalMap, 0, 1)}, 1, 70,
                     200});
    cases.push_back({"twosided_bumpmap_back",
                     {test::diffuse(Spectrum(0.7f)), test::frameAdapter(BsdfType::BumpMap, 0, 0, 3),
                      twoSided(1, 1)},
                     2, 50, 60, true});
    cases.push_back({"normalmap_twosided_back",
                     {test::roughConductor(0.1f, 0.3f), twoSided(0, 0),
                      test::frameAdapter(BsdfType::NormalMap, 1, 1)},
                     2, 50, 60, true});
    return cases;
}

class FrameChi2 : public testing::TestWithParam<FrameCase> {};

TEST_P(FrameChi2, SamplingMatchesPdf) { runFrameChi2(GetParam(), 11); }

INSTANTIATE_TEST_SUITE_P(All, FrameChi2, testing::ValuesIn(makeCases()),
                         [](const testing::TestParamInfo<FrameCase>& info) { return info.param.name; });

/// A twosided over a bumpmap or normalmap is prepared as one leaf (needsTreeWalk, bsdf.h): it must
/// give the tree walk's bits, from either side, textured frames included.
TEST(FrameChi2, TwoSidedOverAMapGivesTheWalksBits) {
    const FrameTextures tex;
    const SurfaceInteraction si = tiltedSurface(tex);
    int cases = 0;
    for (const FrameCase& c : makeCases()) {
        const Span<const Bsdf> bsdfs(c.bsdfs);
        if (bsdfs[c.id].type != BsdfType::TwoSided) continue;
        SCOPED_TRACE(c.name);
        ++cases;
        EXPECT_FALSE(bsdf_detail::needsTreeWalk(bsdfs, c.id));
        const bsdf_detail::LeafOps leaf{bsdfs, si};
        IndependentSampler rng(5, 0, 9);
        for (int i = 0; i < 2000; ++i) {
            const Vec3f wo = sampleUniformSphere(rng.get2D()), wi = sampleUniformSphere(rng.get2D());
            const Spectrum f = evalBsdf(bsdfs, c.id, si, wo, wi), fw = bsdf_detail::compositeEval(bsdfs, leaf, c.id, wo, wi);
            ASSERT_TRUE(f.r == fw.r && f.g == fw.g && f.b == fw.b) << i;
            ASSERT_EQ(pdfBsdf(bsdfs, c.id, si, wo, wi), bsdf_detail::compositePdf(bsdfs, leaf, c.id, wo, wi)) << i;
            const Float uLobe = rng.get1D();
            const Vec2f u = rng.get2D();
            BsdfSample direct, walked;
            const bool a = sampleBsdf(bsdfs, c.id, si, wo, uLobe, u, direct);
            ASSERT_EQ(a, bsdf_detail::compositeSample(bsdfs, leaf, c.id, wo, uLobe, u, walked)) << i;
            if (a) {
                ASSERT_TRUE(direct.wi.x == walked.wi.x && direct.wi.y == walked.wi.y && direct.wi.z == walked.wi.z &&
                            direct.pdf == walked.pdf && direct.weight.r == walked.weight.r &&
                            direct.weight.g == walked.weight.g && direct.weight.b == walked.weight.b)
                    << i;
            }
        }
    }
    EXPECT_EQ(cases, 1);  // twosided_bumpmap_back (normalmap_twosided_back has the map on top)
}

/// The narrow roughness (alpha_u) lies along dp/du: reflected directions spread along the
/// frame's t axis, not along s; turning dp/du by 90° turns the lobe.
TEST(FrameChi2, AnisotropicLobeFollowsDpdu) {
    const std::vector<Bsdf> bsdfs{test::roughConductor(0.02f, 0.4f)};
    for (bool turned : {false, true}) {
        SurfaceInteraction si = test::surfaceAt(Vec3f(0, 0, 1));
        si.dpdu = turned ? Vec3f(0, 1, 0) : Vec3f(1, 0, 0);
        double spreadX = 0, spreadY = 0;
        for (int i = 0; i < 20000; ++i) {
            IndependentSampler rng(uint64_t(i), 0, 5);
            BsdfSample bs;
            if (!sampleBsdf(bsdfs, 0, si, Vec3f(0, 0, 1), rng.get1D(), rng.get2D(), bs)) continue;
            spreadX += std::fabs(bs.wi.x);
            spreadY += std::fabs(bs.wi.y);
        }
        if (turned)
            EXPECT_GT(spreadX, 5 * spreadY);
        else
            EXPECT_GT(spreadY, 5 * spreadX);
    }
}

/// A flat normal map (0.5, 0.5, 1) and a constant height field leave the BSDF unchanged.
TEST(FrameChi2, FlatPerturbationIsTheIdentity) {
    FrameTextures tex;
    for (int i = 0; i < 16; ++i) tex.texels[size_t(i)] = Spectrum(0.3f);
    for (int i = 16; i < 20; ++i) tex.texels[size_t(i)] = Spectrum(0.5f, 0.5f, 1.0f);
    // Isotropic: Mitsuba's adapters orient the perturbed frame's s axis from dp/du in mixed
    // coordinates, which turns an anisotropic lobe even under a flat map.
    const std::vector<Bsdf> bsdfs{test::roughConductor(0.2f, 0.2f),
                                  test::frameAdapter(BsdfType::BumpMap, 0, 0, 5),
                                  test::frameAdapter(BsdfType::NormalMap, 0, 1)};
    SurfaceInteraction si = test::surfaceAt(Vec3f(0, 0, 1));
    si.dpdu = Vec3f(1, 0.5f, 0);
    si.dpdv = Vec3f(-0.5f, 1, 0);
    si.textures = {tex.textures, tex.texels};
    const Vec3f wo = normalize(Vec3f(0.3f, 0.2f, 1)), wi = normalize(Vec3f(-0.2f, 0.4f, 1));
    const Float ref = evalBsdf(bsdfs, 0, si, wo, wi).g;
    EXPECT_GT(ref, 0);
    EXPECT_NEAR(evalBsdf(bsdfs, 1, si, wo, wi).g, ref, 1e-5f * ref);
    EXPECT_NEAR(evalBsdf(bsdfs, 2, si, wo, wi).g, ref, 1e-5f * ref);
}

}  // namespace
}  // namespace caustica
