// White furnace: inside a uniform environment of radiance 1, a closed object that neither absorbs
// nor emits must render as 1 everywhere (energy conservation of the BSDF sampling, NEE + MIS and
// Russian roulette together). Tolerances come from the per-pixel variance of independent runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "render_helpers.h"

namespace caustica::test {
namespace {

std::string furnaceScene(const std::string& shape, const std::string& bsdf, bool hideEmitters = false) {
    std::string dir = (std::filesystem::temp_directory_path() / "caustica_furnace").string();
    std::filesystem::create_directories(dir);
    std::string path = dir + "/furnace_" + std::to_string(std::hash<std::string>{}(shape + bsdf)) +
                       (hideEmitters ? "_h" : "") + ".xml";
    std::ofstream f(path);
    f << R"(<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="-1"/>
    <boolean name="hide_emitters" value=")" << (hideEmitters ? "true" : "false") << R"("/></integrator>
  <sensor type="perspective">
    <float name="fov" value="28"/>
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/>
      <rfilter type="box"/></film>
    <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
  <shape type=")" << shape << R"(">)" << bsdf << R"(</shape>
</scene>
)";
    return path;
}

/// Every pixel within 5 sigma of `expected` (sigma estimated from the runs, so a t-distribution
/// with runs-1 degrees of freedom: allow 1% of the values beyond, far more than the tail of an
/// unbiased estimate needs, far fewer than a biased region makes); exactly `expected` where there
/// is no noise; and the image mean within 4 sigma.
void expectUniform(const Scene& scene, float expected, int runs = 16, int spp = 16) {
    RenderEnsemble e = renderEnsemble(scene, runs, spp);
    size_t outliers = 0;
    for (size_t j = 0; j < e.mean.rgb.size(); ++j) {
        double sigma = std::sqrt(double(e.varianceOfMean.rgb[j]));
        double tol = std::max(5 * sigma, 1e-4);
        if (std::fabs(e.mean.rgb[j] - expected) > tol) ++outliers;
    }
    EXPECT_LE(outliers, e.mean.rgb.size() / 100) << "pixels away from " << expected;
    double z = (meanOf(e.runImageMeans) - expected) / std::sqrt(std::max(varianceOfMeanOf(e.runImageMeans), 1e-12));
    EXPECT_LT(std::fabs(z), 4.0) << "image mean " << meanOf(e.runImageMeans);
}

TEST(WhiteFurnace, DiffuseAlbedoOneSphere) {
    Scene s = loadScene(furnaceScene("sphere", R"(<bsdf type="diffuse"><rgb name="reflectance" value="1, 1, 1"/></bsdf>)"));
    expectUniform(s, 1.0f);
}

TEST(WhiteFurnace, DiffuseAlbedoOneCube) {
    Scene s = loadScene(furnaceScene("cube", R"(<bsdf type="diffuse"><rgb name="reflectance" value="1, 1, 1"/></bsdf>)"));
    expectUniform(s, 1.0f);
}

TEST(WhiteFurnace, GlassSphereNeitherGainsNorLoses) {
    Scene s = loadScene(furnaceScene("sphere", R"(<bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>)"));
    expectUniform(s, 1.0f);
}

TEST(WhiteFurnace, WaterCubeNeitherGainsNorLoses) {
    Scene s = loadScene(furnaceScene("cube", R"(<bsdf type="dielectric"><float name="int_ior" value="1.33"/>
        <float name="ext_ior" value="1.0"/></bsdf>)"));
    expectUniform(s, 1.0f);
}

TEST(WhiteFurnace, PerfectMirrorIsExactlyOne) {
    Scene s = loadScene(furnaceScene("sphere", R"(<bsdf type="conductor"/>)"));
    expectUniform(s, 1.0f, 2, 4);
}

TEST(WhiteFurnace, HiddenEmittersLeaveTheBackgroundBlack) {
    Scene s = loadScene(furnaceScene("sphere", R"(<bsdf type="conductor"/>)", true));
    Image im = renderImage(s, {4, 1, AccelKind::Embree, 0});
    // Corner pixels see only the environment, which is hidden; the mirror still reflects it.
    EXPECT_EQ(im.rgb[0], 0.0f);
    const size_t centre = (size_t(8) * 16 + 8) * 3;
    EXPECT_NEAR(im.rgb[centre], 1.0f, 1e-5);
}

}  // namespace
}  // namespace caustica::test
