// bundled_scenes_test.cpp — the scenes shipped in scenes/ load without errors or warnings.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "caustica/io/scene_loader.h"
#include "scene_test_util.h"

namespace caustica {
namespace {

TEST(BundledScenes, EverySceneLoadsWithoutWarnings) {
    int count = 0;
    for (const auto& dir : std::filesystem::directory_iterator(CAUSTICA_SOURCE_DIR "/scenes")) {
        const auto xml = dir.path() / "scene.xml";
        if (!std::filesystem::exists(xml)) continue;
        SCOPED_TRACE(xml.string());
        std::vector<std::string> warnings;
        Scene s = loadScene(xml.string(), {}, &warnings);
        for (const std::string& w : warnings) ADD_FAILURE() << w;
        EXPECT_FALSE(s.shapes.empty());
        EXPECT_FALSE(s.lights.empty());
        ++count;
    }
    EXPECT_GE(count, 1);
}

TEST(BundledScenes, CornellBoxLoadsLikeMitsuba) {
    std::vector<std::string> warnings;
    Scene s = loadScene(CAUSTICA_SOURCE_DIR "/scenes/cornell-box/scene.xml", {}, &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    EXPECT_EQ(s.shapes.size(), 8u);
    EXPECT_EQ(s.triangles.size(), 6u * 2 + 2u * 12);
    EXPECT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, LightType::Area);
    EXPECT_EQ(s.lights[0].shape, 0u);
    EXPECT_EQ(s.shapes[0].light, 0);
    EXPECT_NEAR(s.lights[0].area, 0.46f * 0.38f, 1e-5f);
    EXPECT_EQ(s.bsdfs.size(), 3u);  // white, red, green: shared by reference
    EXPECT_EQ(s.film.width, 256);
    EXPECT_EQ(s.film.height, 256);
    EXPECT_EQ(s.film.filter.type, FilterType::Box);
    EXPECT_EQ(s.sampleCount, 64);
    EXPECT_EQ(test::integratorParam(s, "max_depth"), "-1");
    EXPECT_NEAR(s.camera.tanHalfX, std::tan(0.5 * 39.3077 * M_PI / 180), 1e-6);
    EXPECT_EQ(s.sourceFile, CAUSTICA_SOURCE_DIR "/scenes/cornell-box/scene.xml");
}

TEST(BundledScenes, CornellBoxDefinesOverrideDefaults) {
    Scene s = loadScene(CAUSTICA_SOURCE_DIR "/scenes/cornell-box/scene.xml",
                        {{"spp", "8"}, {"width", "64"}, {"height", "32"}});
    EXPECT_EQ(s.sampleCount, 8);
    EXPECT_EQ(s.film.width, 64);
    EXPECT_EQ(s.camera.height, 32);
}

}  // namespace
}  // namespace caustica
