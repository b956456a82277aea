#include "caustica/util/transform.h"

#include <stdexcept>

namespace caustica {

bool invert(const Matrix4& a, Matrix4& out) {
    double inv[16], m[16];
    for (int i = 0; i < 16; ++i) m[i] = a.m[i / 4][i % 4];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] +
             m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] -
             m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] +
             m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] -
              m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] -
             m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] +
             m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] -
             m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] +
              m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] +
             m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] -
             m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] +
              m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] -
              m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] -
             m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] +
             m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] -
              m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] +
              m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (det == 0 || !std::isfinite(det)) return false;
    double invDet = 1.0 / det;
    for (int i = 0; i < 16; ++i) out.m[i / 4][i % 4] = Float(inv[i] * invDet);
    return true;
}

Transform Transform::fromMatrix(const Matrix4& m) {
    Matrix4 inv;
    if (!invert(m, inv)) throw std::domain_error("transform matrix is singular");
    return {m, inv};
}

Transform translate(Vec3f t) {
    Matrix4 m, inv;
    m.m[0][3] = t.x; m.m[1][3] = t.y; m.m[2][3] = t.z;
    inv.m[0][3] = -t.x; inv.m[1][3] = -t.y; inv.m[2][3] = -t.z;
    return {m, inv};
}

Transform scale(Vec3f s) {
    Matrix4 m, inv;
    m.m[0][0] = s.x; m.m[1][1] = s.y; m.m[2][2] = s.z;
    inv.m[0][0] = 1 / s.x; inv.m[1][1] = 1 / s.y; inv.m[2][2] = 1 / s.z;
    if (s.x == 0 || s.y == 0 || s.z == 0) throw std::domain_error("scale by zero");
    return {m, inv};
}

Transform rotate(Vec3f axis, Float angleDegrees) {
    if (lengthSquared(axis) == 0) throw std::domain_error("rotation axis is zero");
    Vec3f a = normalize(axis);
    Float s = std::sin(radians(angleDegrees)), c = std::cos(radians(angleDegrees));
    Matrix4 m;
    m.m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
    m.m[0][1] = a.x * a.y * (1 - c) - a.z * s;
    m.m[0][2] = a.x * a.z * (1 - c) + a.y * s;
    m.m[1][0] = a.x * a.y * (1 - c) + a.z * s;
    m.m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
    m.m[1][2] = a.y * a.z * (1 - c) - a.x * s;
    m.m[2][0] = a.x * a.z * (1 - c) - a.y * s;
    m.m[2][1] = a.y * a.z * (1 - c) + a.x * s;
    m.m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
    return {m, m.transposed()};
}

Transform lookAt(Vec3f origin, Vec3f target, Vec3f up) {
    Vec3f dir = target - origin;
    if (lengthSquared(dir) == 0) throw std::domain_error("lookat: origin and target coincide");
    dir = normalize(dir);
    Vec3f left = cross(up, dir);
    if (lengthSquared(left) == 0) throw std::domain_error("lookat: up is parallel to the view direction");
    left = normalize(left);
    Vec3f newUp = cross(dir, left);
    Matrix4 m;
    for (int r = 0; r < 3; ++r) {
        m.m[r][0] = left[r];
        m.m[r][1] = newUp[r];
        m.m[r][2] = dir[r];
        m.m[r][3] = origin[r];
    }
    return Transform::fromMatrix(m);
}

}  // namespace caustica
