// load_scene.cpp — caustica::loadScene: parse the XML into entities, then build the Scene.
#include <cstdio>

#include "caustica/io/mitsuba/scene_builder.h"
#include "caustica/io/mitsuba/xml_parser.h"
#include "caustica/io/scene_loader.h"

namespace caustica {

Scene loadScene(const std::string& path, const std::map<std::string, std::string>& defines,
                std::vector<std::string>* warnings) {
    std::vector<std::string> local;
    std::vector<std::string>& sink = warnings ? *warnings : local;
    const size_t first = sink.size();
    mitsuba::SceneDescription desc = mitsuba::parseSceneXml(path, defines, sink);
    Scene scene = mitsuba::buildScene(desc, sink);
    if (!warnings)
        for (size_t i = first; i < sink.size(); ++i)
            std::fprintf(stderr, "warning: %s\n", sink[i].c_str());
    return scene;
}

}  // namespace caustica
