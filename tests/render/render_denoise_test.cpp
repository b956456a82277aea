// render_denoise_test.cpp — the guide AOVs `render --denoise` adds and where its copies go.
#include <gtest/gtest.h>

#include "caustica/render/render_denoise.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

TEST(RenderDenoise, AddsOnlyTheMissingGuides) {
    const AovSpec none = withDenoiseGuides(AovSpec{}, true);
    EXPECT_EQ(none.text(), "denoise.albedo:albedo,denoise.normal:sh_normal,denoise.depth:depth,"
                           "denoise.variance:variance");
    EXPECT_EQ(withDenoiseGuides(AovSpec{}, false).text(),
              "denoise.albedo:albedo,denoise.normal:sh_normal,denoise.depth:depth");
    // The user's own layers of a guide type are used as they are, a geometric normal included.
    const AovSpec mine = withDenoiseGuides(parseAovSpec("dd.y:depth,gn:geo_normal,a:albedo", "test"), false);
    EXPECT_EQ(mine.text(), "dd.y:depth,gn:geo_normal,a:albedo");
}

TEST(RenderDenoise, RefusesMoreLayersThanTheFilmHolds) {
    std::string list;
    for (int i = 0; i < kMaxAovLayers; ++i) list += (i ? ",p" : "p") + std::to_string(i) + ":position";
    EXPECT_THROW(withDenoiseGuides(parseAovSpec(list, "test"), true), Error);
}

TEST(RenderDenoise, DenoisedCopyGoesBesideTheOutput) {
    EXPECT_EQ(denoisedOutputPath("out/a.exr"), "out/a.denoised.exr");
    EXPECT_EQ(denoisedOutputPath("a.b.png"), "a.b.denoised.png");
    EXPECT_EQ(denoisedOutputPath("img.pfm"), "img.denoised.pfm");
}

}  // namespace
}  // namespace caustica
