// camera.h — Mitsuba's perspective sensor: pinhole camera looking down +z in camera space.
#pragma once

#include "caustica/scene/ray.h"
#include "caustica/util/transform.h"

namespace caustica {

struct Camera {
    Transform worldFromCamera;  // Mitsuba's sensor to_world (camera +x points left, +y up)
    Float tanHalfX = 1, tanHalfY = 1;  // half-extent of the image plane at distance 1
    int width = 0, height = 0;         // full film size in pixels
    Float nearClip = 1e-2f, farClip = 1e4f;
};

/// Primary ray through film position `film` in pixels ((0,0) = top-left corner of the image).
CA_HD_INLINE Ray generateCameraRay(const Camera& cam, Vec2f film) {
    Float u = film.x / Float(cam.width), v = film.y / Float(cam.height);
    // Mitsuba flips both axes: +x on the film (right) is -x in camera space (which points left).
    Vec3f dCam(-(2 * u - 1) * cam.tanHalfX, -(2 * v - 1) * cam.tanHalfY, 1);
    Vec3f dirCam = normalize(dCam);
    Float tNear = cam.nearClip / dirCam.z, tFar = cam.farClip / dirCam.z;
    Vec3f o = cam.worldFromCamera.applyPoint(dirCam * tNear);
    Vec3f d = normalize(cam.worldFromCamera.applyVector(dirCam));
    // Distances along d in world units: rescale by the transform's stretch of the direction.
    Float stretch = length(cam.worldFromCamera.applyVector(dirCam));
    return Ray{o, d, (tFar - tNear) * stretch};
}

}  // namespace caustica
