// The public BSDF entry points (evalBsdf, pdfBsdf, evalPdfBsdf, sampleBsdf, isDeltaBsdf,
// isSpecularBsdf; scene/bsdf.h) go straight to a plain leaf instead of walking the tree
// (bsdf_composite.h). They must give the walk's values bit for bit, or images would change with
// the shortcut; evalPdfBsdf must give what evalBsdf and pdfBsdf give, for composites too, and
// BsdfAtVertex (one resolve for a vertex's two queries) what evalPdfBsdf and sampleBsdf give.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "caustica/scene/bsdf.h"
#include "caustica/util/rng.h"
#include "scene/bsdf_more_util.h"
#include "scene/bsdf_test_util.h"

namespace caustica {
namespace {

using test::append;

template <class T>
bool sameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

bool sameBits(const BsdfSample& a, const BsdfSample& b) {
    return sameBits(a.wi, b.wi) && sameBits(a.weight, b.weight) && sameBits(a.pdf, b.pdf) &&
           sameBits(a.eta, b.eta) && a.delta == b.delta;
}

struct Case {
    std::string name;
    uint32_t id;
};

/// Every leaf type, and composites for evalPdfBsdf's general branch.
std::vector<Case> buildCases(std::vector<Bsdf>& bsdfs) {
    std::vector<Case> cases;
    auto leaf = [&](const std::string& name, const Bsdf& b) { cases.push_back({name, append(bsdfs, b)}); };
    leaf("diffuse", test::diffuse(Spectrum(0.2f, 0.5f, 0.8f)));
    leaf("roughconductor", test::roughConductor(0.3f, 0.1f));
    leaf("beckmann", test::beckmannConductor(0.2f, 0.2f));
    leaf("plastic", test::plastic());
    leaf("conductor", test::conductor(Spectrum(0.2f), Spectrum(3.f)));
    leaf("dielectric", test::dielectric(1.5f));
    leaf("roughdielectric", test::roughDielectric(1.33f, 0.2f, 0.2f));
    leaf("thindielectric", test::thinDielectric(1.5f));
    cases.push_back({"twosided", test::addTwoSided(bsdfs, test::diffuse(Spectrum(0.7f)), test::plastic())});
    // Twosided over two leaves is prepared as one leaf (needsTreeWalk); over a composite it walks.
    cases.push_back({"twosided-diffuse",
                     test::addTwoSided(bsdfs, test::diffuse(Spectrum(0.7f, 0.2f, 0.4f)), test::diffuse(Spectrum(0.3f)))});
    cases.push_back({"twosided-conductor", test::addTwoSided(bsdfs, test::roughConductor(0.3f, 0.1f),
                                                             test::dielectric(1.5f))});
    {
        const uint32_t blended = test::blend(bsdfs, 0.4f, test::diffuse(Spectrum(0.5f)), test::roughConductor(0.2f, 0.2f));
        Bsdf twoSided;
        twoSided.type = BsdfType::TwoSided;
        twoSided.front = blended;
        twoSided.back = blended;
        cases.push_back({"twosided-blend", append(bsdfs, twoSided)});
    }
    cases.push_back({"blend", test::blend(bsdfs, 0.3f, test::diffuse(Spectrum(0.4f)), test::dielectric(1.5f))});
    cases.push_back({"mask", test::mask(bsdfs, 0.6f, test::roughConductor(0.2f, 0.2f))});
    return cases;
}

/// A random unit direction (either hemisphere) from two uniform numbers.
Vec3f randomDirection(IndependentSampler& rng) {
    const Float z = 1 - 2 * rng.get1D(), phi = 2 * kPi * rng.get1D();
    const Float r = std::sqrt(max(Float(0), 1 - z * z));
    return Vec3f(r * std::cos(phi), r * std::sin(phi), z);
}

TEST(BsdfLeafPath, GivesTheTreeWalksBits) {
    std::vector<Bsdf> bsdfs;
    const std::vector<Case> cases = buildCases(bsdfs);
    const Span<const Bsdf> span(bsdfs.data(), bsdfs.size());
    SurfaceInteraction si = test::surfaceAt(Vec3f(0.2f, 1, -0.3f));
    si.dpdu = normalize(Vec3f(1, 0.1f, 0.4f));  // a shading frame from dp/du, as on a mesh
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const bsdf_detail::LeafOps leaf{span, si};
        EXPECT_EQ(isDeltaBsdf(span, c.id), bsdf_detail::compositeIsDelta(span, leaf, c.id));
        IndependentSampler rng(7, 0, 11);
        for (int i = 0; i < 4000; ++i) {
            const Vec3f wo = randomDirection(rng), wi = randomDirection(rng);
            const Spectrum f = evalBsdf(span, c.id, si, wo, wi);
            const Float pdf = pdfBsdf(span, c.id, si, wo, wi);
            ASSERT_TRUE(sameBits(f, bsdf_detail::compositeEval(span, leaf, c.id, wo, wi))) << i;
            ASSERT_TRUE(sameBits(pdf, bsdf_detail::compositePdf(span, leaf, c.id, wo, wi))) << i;
            Float fusedPdf = -1;
            ASSERT_TRUE(sameBits(f, evalPdfBsdf(span, c.id, si, wo, wi, fusedPdf))) << i;
            ASSERT_TRUE(sameBits(pdf, fusedPdf)) << i;

            const Float uLobe = rng.get1D();
            const Vec2f u = rng.get2D();
            BsdfSample direct, walked;
            const bool a = sampleBsdf(span, c.id, si, wo, uLobe, u, direct);
            const bool b = bsdf_detail::compositeSample(span, leaf, c.id, wo, uLobe, u, walked);
            ASSERT_EQ(a, b) << i;
            if (a) {
                ASSERT_TRUE(sameBits(direct, walked)) << i;
            }
        }
    }
}

TEST(BsdfLeafPath, WalksOnlyWhereItMust) {
    std::vector<Bsdf> bsdfs;
    const std::vector<Case> cases = buildCases(bsdfs);
    const Span<const Bsdf> span(bsdfs.data(), bsdfs.size());
    for (const Case& c : cases) {
        const bool walks = c.name == "blend" || c.name == "mask" || c.name == "twosided-blend";
        EXPECT_EQ(bsdf_detail::needsTreeWalk(span, c.id), walks) << c.name;
    }
}

TEST(BsdfAtVertex, GivesEvalPdfBsdfsAndSampleBsdfsBits) {
    std::vector<Bsdf> bsdfs;
    const std::vector<Case> cases = buildCases(bsdfs);
    const Span<const Bsdf> span(bsdfs.data(), bsdfs.size());
    SurfaceInteraction si = test::surfaceAt(Vec3f(-0.4f, 0.8f, 0.2f));
    si.dpdu = normalize(Vec3f(0.3f, 0.2f, 1));
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        IndependentSampler rng(3, 0, 5);
        for (int i = 0; i < 2000; ++i) {
            const Vec3f wo = randomDirection(rng);
            const BsdfAtVertex at(span, c.id, si, wo);
            for (int q = 0; q < 2; ++q) {  // the prepared vertex answers any number of queries
                const Vec3f wi = randomDirection(rng);
                Float expectedPdf = -1, pdf = -2;
                const Spectrum expected = evalPdfBsdf(span, c.id, si, wo, wi, expectedPdf);
                ASSERT_TRUE(sameBits(expected, at.evalPdf(wi, pdf))) << i;
                ASSERT_TRUE(sameBits(expectedPdf, pdf)) << i;

                const Float uLobe = rng.get1D();
                const Vec2f u = rng.get2D();
                BsdfSample want, got;
                const bool a = sampleBsdf(span, c.id, si, wo, uLobe, u, want);
                ASSERT_EQ(a, at.sample(uLobe, u, got)) << i;
                if (a) {
                    ASSERT_TRUE(sameBits(want, got)) << i;
                }
            }
        }
    }
}

TEST(BsdfLeafPath, SpecularTestMatchesTheWalk) {
    std::vector<Bsdf> bsdfs;
    const std::vector<Case> cases = buildCases(bsdfs);
    const Span<const Bsdf> span(bsdfs.data(), bsdfs.size());
    const SurfaceInteraction si{};
    const bsdf_detail::LeafOps leaf{span, si};
    for (const Case& c : cases) {
        for (Float threshold : {Float(0), Float(0.1), Float(0.25), Float(0.5)}) {
            SCOPED_TRACE(c.name + " threshold " + std::to_string(threshold));
            bool walked = true;
            bsdf_detail::forEachLeaf<true>(span, leaf, c.id, false, leaf.normal(), [&](uint32_t l, Float, bool) {
                walked = walked && (threshold > 0 ? bsdf_detail::isSpecularLeaf(span, l, threshold)
                                                  : bsdf_detail::leafIsDelta(span, l));
            });
            EXPECT_EQ(isSpecularBsdf(span, c.id, threshold), walked);
        }
    }
}

}  // namespace
}  // namespace caustica
