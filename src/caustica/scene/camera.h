// camera.h — Mitsuba 3's projective sensors as one plain device struct with a type tag:
// `perspective` (pinhole), `thinlens` (perspective with a disk aperture focused at a distance) and
// `orthographic`. All look down +z in camera space; Mitsuba flips both film axes (camera +x
// points left, +y up). A crop window renders film pixels [crop, crop + film size) of the full
// width x height image: film position (0, 0) of a render is full-image position (cropX, cropY).
// A stereo rig (scene/stereo_rig.h derives it) renders both eyes side by side on one film twice
// as wide: film x in [0, eyeWidth) is the left eye, [eyeWidth, 2 eyeWidth) the right eye, each
// with its own camera-to-world transform and frustum shift (docs/STEREO.md).
#pragma once

#include <cstdint>

#include "caustica/scene/ray.h"
#include "caustica/util/sampling.h"
#include "caustica/util/transform.h"

namespace caustica {

enum class CameraType : uint32_t { Perspective, ThinLens, Orthographic };

struct Camera {
    CameraType type = CameraType::Perspective;
    Transform worldFromCamera;  // Mitsuba's sensor to_world (camera +x points left, +y up)
    // Perspective, thin lens: half-extent of the image plane at distance 1 (tan of half the
    // field of view). Orthographic: half-extent in camera units (1 and 1/aspect, as Mitsuba:
    // to_world's scale sets the extent in the scene).
    Float tanHalfX = 1, tanHalfY = 1;
    int width = 0, height = 0;  // full film size in pixels (crop windows included)
    int cropX = 0, cropY = 0;   // crop offset in pixels: where the rendered window starts
    Float nearClip = 1e-2f, farClip = 1e4f;
    Float apertureRadius = 0;   // thin lens: radius of the aperture disk (camera units)
    Float focusDistance = 1e4f; // thin lens: distance of the plane in focus (Mitsuba: far_clip)
    // Horizontal shift of the image plane at distance 1 in camera x units (an off-axis eye's
    // asymmetric frustum; 0 for an ordinary camera).
    Float shiftX = 0;
    // Stereo rig: eyeWidth > 0 is the rendered width of one eye (film width = 2 eyeWidth); eye 0
    // (left) and 1 (right) then use worldFromEye[eye] and eyeShift[eye] instead of
    // worldFromCamera and shiftX. 0: mono.
    int eyeWidth = 0;
    Transform worldFromEye[2];
    Float eyeShift[2] = {0, 0};
};

/// Which eye film x belongs to (0 left, 1 right; 0 for a mono camera).
CA_HD_INLINE int cameraEyeOf(const Camera& cam, Float filmX) {
    return cam.eyeWidth > 0 && filmX >= Float(cam.eyeWidth) ? 1 : 0;
}

/// Whether generateCameraRay needs a lens sample (a thin lens with an open aperture).
CA_HD_INLINE bool cameraNeedsLensSample(const Camera& cam) {
    return cam.type == CameraType::ThinLens && cam.apertureRadius > 0;
}

/// Primary ray of a camera placed by `worldFromCamera` with frustum shift `shift` through film
/// position `film` in pixels of one eye's rendered (cropped) image ((0,0) = its top-left corner);
/// `uLens` picks the point on a thin lens' aperture (Mitsuba's sample_ray of perspective.cpp,
/// thinlens.cpp, orthographic.cpp).
CA_HD_INLINE Ray generateEyeRay(const Camera& cam, const Transform& worldFromCamera, Float shift, Vec2f film,
                                Vec2f uLens) {
    const Float u = (film.x + Float(cam.cropX)) / Float(cam.width);
    const Float v = (film.y + Float(cam.cropY)) / Float(cam.height);
    // Mitsuba flips both axes: +x on the film (right) is -x in camera space (which points left).
    const Float px = -(2 * u - 1) * cam.tanHalfX + shift, py = -(2 * v - 1) * cam.tanHalfY;
    if (cam.type == CameraType::Orthographic) {
        const Vec3f o = worldFromCamera.applyPoint(Vec3f(px, py, cam.nearClip));
        const Vec3f d = worldFromCamera.applyVector(Vec3f(0, 0, 1));
        return Ray{o, normalize(d), cam.farClip - cam.nearClip};
    }
    Vec3f dirCam = normalize(Vec3f(px, py, 1));
    Vec3f originCam(0);
    if (cam.type == CameraType::ThinLens) {
        // The ray from a point on the aperture through the in-focus point of the pinhole ray.
        const Vec2f disk = sampleConcentricDisk(uLens) * cam.apertureRadius;
        originCam = Vec3f(disk.x, disk.y, 0);
        const Vec3f focus = Vec3f(px, py, 1) * cam.focusDistance;
        dirCam = normalize(focus - originCam);
    }
    const Float tNear = cam.nearClip / dirCam.z, tFar = cam.farClip / dirCam.z;
    const Vec3f o = worldFromCamera.applyPoint(originCam + dirCam * tNear);
    const Vec3f d = normalize(worldFromCamera.applyVector(dirCam));
    // Distances along d in world units: rescale by the transform's stretch of the direction.
    const Float stretch = length(worldFromCamera.applyVector(dirCam));
    return Ray{o, d, (tFar - tNear) * stretch};
}

/// Primary ray through film position `film` in pixels of the rendered film; a stereo rig picks
/// the eye from film x (cameraEyeOf) and traces from that eye's camera.
CA_HD_INLINE Ray generateCameraRay(const Camera& cam, Vec2f film, Vec2f uLens = Vec2f(0.5f, 0.5f)) {
    if (cam.eyeWidth > 0) {
        const int eye = cameraEyeOf(cam, film.x);
        const Vec2f local(film.x - Float(eye * cam.eyeWidth), film.y);
        return generateEyeRay(cam, cam.worldFromEye[eye], cam.eyeShift[eye], local, uLens);
    }
    return generateEyeRay(cam, cam.worldFromCamera, cam.shiftX, film, uLens);
}

/// Where the eye of film x sits in the world (the camera's centre for a mono camera).
CA_HD_INLINE Vec3f cameraEyePosition(const Camera& cam, Float filmX) {
    return cam.eyeWidth > 0 ? cam.worldFromEye[cameraEyeOf(cam, filmX)].applyPoint(Vec3f(0))
                            : cam.worldFromCamera.applyPoint(Vec3f(0));
}

/// The camera ray of a pixel sample, drawing the lens sample from `sampler` only when the camera
/// needs one (so that pinhole renders keep their random-number layout).
template <class Sampler>
CA_HD Ray sampleCameraRay(const Camera& cam, Vec2f film, Sampler& sampler) {
    const Vec2f uLens = cameraNeedsLensSample(cam) ? sampler.get2D() : Vec2f(0.5f, 0.5f);
    return generateCameraRay(cam, film, uLens);
}

}  // namespace caustica
