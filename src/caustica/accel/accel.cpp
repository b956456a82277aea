// accel.cpp — backend selection for Accel (see accel.h).
#include "caustica/accel/accel.h"

#include "caustica/util/error.h"

namespace caustica {

AccelKind parseAccelKind(const std::string& name) {
    if (name == "bvh") return AccelKind::Bvh;
    if (name == "embree") return AccelKind::Embree;
    throw Error("unknown acceleration structure '" + name + "' (expected 'bvh' or 'embree')");
}

const char* accelKindName(AccelKind kind) { return kind == AccelKind::Embree ? "embree" : "bvh"; }

Accel::Accel(const Scene& scene, AccelKind kind, const BvhBuildOptions& bvhOptions,
             const EmbreeSceneOptions& embreeOptions)
    : kind_(kind), scene_(scene.view()) {
    if (kind == AccelKind::Embree)
        embree_ = std::make_unique<EmbreeScene>(scene, embreeOptions);
    else
        bvh_ = std::make_unique<Bvh>(buildBvh(scene, bvhOptions));
}

std::string Accel::description() const {
    if (!embree_) return accelKindName(kind_);
    const int width = embree_->packetWidth();
    return std::string("embree (") + embreeIsaName(embree_->isa()) + ", " +
           (width > 1 ? std::to_string(width) + "-ray packets)" : "single rays)");
}

Accel::~Accel() = default;
Accel::Accel(Accel&&) noexcept = default;
Accel& Accel::operator=(Accel&&) noexcept = default;

}  // namespace caustica
