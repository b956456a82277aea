// integrator_registry.h — the integrators a render can run, by name: each entry says whether a GPU
// runs it with the given request and makes its session (integrator_session.h). Adding an
// integrator is one entry here plus its session; neither the CLI nor the session loop changes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/distributed/communicator.h"
#include "caustica/integrators/integrator_params.h"
#include "caustica/parallel/device.h"
#include "caustica/render/integrator_session.h"
#include "caustica/render/render_request.h"
#include "caustica/scene/scene.h"

namespace caustica {

/// What a session is made from. The scene and accel outlive the session.
struct SessionContext {
    const Scene& scene;
    const Accel& accel;
    Device device;
    uint64_t seed;
    const RenderRequest& request;
    IntegratorParams& params;  // the scene's <integrator> parameters and the command line's
    /// The identity of the checkpoint being resumed, or nullptr: settings left to a default that
    /// depends on the device (mlt's chain count) are taken from it.
    const RenderIdentity* resumeFrom = nullptr;
    /// The ranks this render is spread over (distributed/communicator.h); a single process is
    /// rank 0 of 1. Every rank makes the same session and calls step() in lockstep.
    Communicator& comm = singleProcess();
};

struct IntegratorEntry {
    const char* name;
    const char* summary;  // one line for --help
    /// The command-line options that set its parameters.
    const std::vector<IntegratorOption>& options;
    /// Whether the GPU driver runs this integrator with these parameters; empty when it does,
    /// else the reason (one line).
    std::string (*gpuRefusal)(IntegratorParams& params);
    /// Its settings in one line, for `caustica info` ("max_depth -1, rr_depth 5, ...").
    std::string (*describe)(IntegratorParams& params);
    std::unique_ptr<IntegratorSession> (*make)(const SessionContext& context);
};

/// Every integrator, in the order `caustica info` lists them.
const std::vector<IntegratorEntry>& integratorRegistry();
/// The entry named `name`; throws caustica::Error listing the names when there is none.
const IntegratorEntry& findIntegrator(const std::string& name);
/// "path, direct, mlt".
std::string integratorNames();

/// `spec` as the integrator named `integrator` reads it, with the command line's parameters.
IntegratorParams integratorParams(const IntegratorSpec& spec, const std::string& integrator,
                                  const std::vector<IntegratorParam>& commandLine);

/// The sessions (pass_session.cpp, mlt_session.cpp, sppm_session.cpp) and their registry functions.
std::unique_ptr<IntegratorSession> makePathSession(const SessionContext& context);
std::unique_ptr<IntegratorSession> makeDirectSession(const SessionContext& context);
std::unique_ptr<IntegratorSession> makeWhittedSession(const SessionContext& context);
std::unique_ptr<IntegratorSession> makeMltSession(const SessionContext& context);
std::unique_ptr<IntegratorSession> makeSppmSession(const SessionContext& context);
std::unique_ptr<IntegratorSession> makePpmSession(const SessionContext& context);
std::string describePath(IntegratorParams& params);
std::string describeDirect(IntegratorParams& params);
std::string describeMlt(IntegratorParams& params);
std::string describeSppm(IntegratorParams& params);
std::string describePpm(IntegratorParams& params);
std::string mltGpuRefusal(IntegratorParams& params);

}  // namespace caustica
