// py_options.h — the keyword arguments of caustica.render() / caustica.Renderer() turned into
// render/'s RenderRequest, with each bad value refused as caustica::Error (one line naming the
// keyword), as the command line refuses a bad option.
#pragma once

#include <map>
#include <optional>
#include <string>

#include <pybind11/pybind11.h>

#include "caustica/render/render_request.h"

namespace caustica::py {

/// The keywords of a render besides the scene. None (py::none) leaves a setting to the scene.
struct RenderKeywords {
    pybind11::object integrator, spp, time, device, seed, resolution, aovs, stereo, threads, sppPerPass;
    pybind11::dict integratorParams;  // **kwargs: the integrator's parameters by name (max_depth=8)
};

/// The request for `keywords`; `defines`: the values the scene was loaded with.
RenderRequest renderRequest(const RenderKeywords& keywords, const std::map<std::string, std::string>& defines);
/// threads=N, checked (1..4096); nullopt for None.
std::optional<int> threadCount(const pybind11::object& threads);
/// A keyword value as the scene file would write it: True -> "true", 3 -> "3", "x" -> "x".
std::string valueText(const pybind11::handle& value, const std::string& keyword);

}  // namespace caustica::py
