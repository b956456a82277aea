// accel.h — the scene's ray-tracing acceleration structure, own BVH or Embree, chosen at run time.
// Integrators are templates over the intersector type and reach it through Accel::visit, so the
// choice costs one branch per launch, not a virtual call per ray.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "caustica/accel/bvh.h"
#include "caustica/accel/embree_accel.h"
#include "caustica/accel/intersector.h"
#include "caustica/scene/scene.h"

namespace caustica {

enum class AccelKind { Bvh, Embree };

/// "bvh" or "embree"; anything else throws caustica::Error.
AccelKind parseAccelKind(const std::string& name);
/// The name parseAccelKind accepts for `kind`.
const char* accelKindName(AccelKind kind);

/// Owns the acceleration structure of one Scene. The Scene is held by reference: its arrays are
/// read during traversal (SceneView spans, Embree's sphere callbacks), so the Scene must outlive
/// the Accel and must not be modified while it exists.
///
///     Accel accel(scene, AccelKind::Embree);
///     accel.visit([&](const auto& intersector) { render(intersector, ...); });
class Accel {
public:
    Accel(const Scene& scene, AccelKind kind, const BvhBuildOptions& bvhOptions = {},
          const EmbreeSceneOptions& embreeOptions = {});
    ~Accel();
    Accel(Accel&&) noexcept;
    Accel& operator=(Accel&&) noexcept;

    /// Calls f(BvhIntersector) or f(EmbreeIntersector); both calls must return the same type.
    template <class F>
    decltype(auto) visit(F&& f) const {
        if (kind_ == AccelKind::Embree) return std::forward<F>(f)(embree_->intersector());
        return std::forward<F>(f)(BvhIntersector{bvh_->view(), scene_});
    }

    AccelKind kind() const { return kind_; }
    /// The own BVH (its statistics for `caustica info`), or nullptr for the Embree backend.
    const Bvh* bvh() const { return bvh_.get(); }
    /// "bvh", or "embree (sse4.2, 4-ray packets)" / "embree (widest, 16-ray packets)": the backend
    /// and, for Embree, its instruction-set cap and the packets it traces.
    std::string description() const;
    const SceneView& sceneView() const { return scene_; }

private:
    AccelKind kind_;
    SceneView scene_;
    std::unique_ptr<Bvh> bvh_;
    std::unique_ptr<EmbreeScene> embree_;
};

}  // namespace caustica
