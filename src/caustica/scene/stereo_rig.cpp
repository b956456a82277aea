#include "caustica/scene/stereo_rig.h"

#include <cmath>
#include <cstdio>

#include "caustica/util/error.h"

namespace caustica {

StereoMode parseStereoMode(const std::string& name) {
    if (name == "off") return StereoMode::Off;
    if (name == "off-axis") return StereoMode::OffAxis;
    if (name == "parallel") return StereoMode::Parallel;
    if (name == "toe-in") return StereoMode::ToeIn;
    throw Error("unknown stereo mode '" + name + "' (use off-axis, parallel or toe-in)");
}

const char* stereoModeName(StereoMode mode) {
    switch (mode) {
        case StereoMode::OffAxis: return "off-axis";
        case StereoMode::Parallel: return "parallel";
        case StereoMode::ToeIn: return "toe-in";
        case StereoMode::Off: break;
    }
    return "off";
}

void checkStereoSettings(const StereoSettings& s) {
    if (s.mode == StereoMode::Off) throw Error("--stereo: no stereo mode given");
    auto text = [](Float v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", double(v));
        return std::string(buf);
    };
    if (!(s.interocular > 0) || !std::isfinite(s.interocular))
        throw Error("--interocular " + text(s.interocular) + ": must be a positive, finite distance");
    if (!(s.convergence > 0) || !std::isfinite(s.convergence))
        throw Error("--convergence " + text(s.convergence) + ": must be a positive, finite distance");
}

int makeStereoRig(Camera& camera, int filmWidth, const StereoSettings& s) {
    checkStereoSettings(s);
    if (camera.type == CameraType::Orthographic)
        throw Error("--stereo: an orthographic sensor has no centre of projection; use a perspective or thinlens "
                    "sensor");
    if (camera.eyeWidth > 0) throw Error("--stereo: the camera is a stereo rig already");
    if (filmWidth <= 0 || filmWidth > (1 << 24)) throw Error("--stereo: bad film width");
    // World distances in camera units (to_world may scale).
    const Float unitX = length(camera.worldFromCamera.applyVector(Vec3f(1, 0, 0)));
    const Float unitZ = length(camera.worldFromCamera.applyVector(Vec3f(0, 0, 1)));
    const Float half = 0.5f * s.interocular / unitX, converge = s.convergence / unitZ;
    for (int eye = 0; eye < 2; ++eye) {
        const Float x = eye == 0 ? half : -half;  // camera +x points left: the left eye at +x
        Transform eyeFromRig = translate(Vec3f(x, 0, 0));
        camera.eyeShift[eye] = 0;
        if (s.mode == StereoMode::OffAxis) {
            // The ray of film coordinate p from the eye meets z = C at x + C (p + shift); the
            // centre's ray at C p: equal for shift = -x / C (zero parallax on that plane).
            camera.eyeShift[eye] = -x / converge;
        } else if (s.mode == StereoMode::ToeIn) {
            // Rotate the eye's +z towards the convergence point (0, 0, C): new z = (-x, 0, C) / n,
            // new x = (C, 0, x) / n, y unchanged (right-handed, a rotation about y).
            const Float n = std::sqrt(x * x + converge * converge);
            Matrix4 r;
            r.m[0][0] = converge / n; r.m[0][2] = -x / n;
            r.m[2][0] = x / n;        r.m[2][2] = converge / n;
            Matrix4 rInv = r;  // a rotation's inverse is its transpose
            rInv.m[0][2] = r.m[2][0];
            rInv.m[2][0] = r.m[0][2];
            eyeFromRig = eyeFromRig * Transform(r, rInv);
        }
        camera.worldFromEye[eye] = camera.worldFromCamera * eyeFromRig;
    }
    camera.eyeWidth = filmWidth;
    return 2 * filmWidth;
}

void applyStereo(Scene& scene, const StereoSettings& settings) {
    if (settings.mode == StereoMode::Off) return;
    scene.film.eyeWidth = scene.film.width;
    scene.film.width = makeStereoRig(scene.camera, scene.film.width, settings);
}

Camera eyeCamera(const Camera& rig, int eye) {
    Camera c = rig;
    if (rig.eyeWidth <= 0) return c;
    c.worldFromCamera = rig.worldFromEye[eye];
    c.shiftX = rig.eyeShift[eye];
    c.eyeWidth = 0;
    return c;
}

}  // namespace caustica
