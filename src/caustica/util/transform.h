// transform.h — 4x4 affine/projective transforms with cached inverse (row-major m[row][col]).
#pragma once

#include "caustica/util/math.h"

namespace caustica {

struct Matrix4 {
    Float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

    CA_HD static Matrix4 identity() { return Matrix4{}; }
    CA_HD Matrix4 operator*(const Matrix4& b) const {
        Matrix4 r;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                Float s = 0;
                for (int k = 0; k < 4; ++k) s += m[i][k] * b.m[k][j];
                r.m[i][j] = s;
            }
        return r;
    }
    CA_HD Matrix4 transposed() const {
        Matrix4 r;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) r.m[i][j] = m[j][i];
        return r;
    }
};

/// General 4x4 inverse (cofactor expansion in double precision). Returns false if singular.
bool invert(const Matrix4& a, Matrix4& out);

/// A transform and its inverse. Names follow "toFromFrom": worldFromObject.apply(pObject).
struct Transform {
    Matrix4 m, mInv;

    Transform() = default;
    CA_HD Transform(const Matrix4& m_, const Matrix4& mInv_) : m(m_), mInv(mInv_) {}
    /// Host only: builds the inverse; throws std::domain_error for a singular matrix.
    static Transform fromMatrix(const Matrix4& m);

    CA_HD Transform inverse() const { return {mInv, m}; }
    CA_HD Transform operator*(const Transform& b) const { return {m * b.m, b.mInv * mInv}; }

    CA_HD Vec3f applyPoint(Vec3f p) const {
        Float x = m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3];
        Float y = m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3];
        Float z = m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3];
        Float w = m.m[3][0] * p.x + m.m[3][1] * p.y + m.m[3][2] * p.z + m.m[3][3];
        return w == 1 ? Vec3f(x, y, z) : Vec3f(x, y, z) / w;
    }
    CA_HD Vec3f applyVector(Vec3f v) const {
        return {m.m[0][0] * v.x + m.m[0][1] * v.y + m.m[0][2] * v.z,
                m.m[1][0] * v.x + m.m[1][1] * v.y + m.m[1][2] * v.z,
                m.m[2][0] * v.x + m.m[2][1] * v.y + m.m[2][2] * v.z};
    }
    /// Normals transform by the inverse transpose.
    CA_HD Vec3f applyNormal(Vec3f n) const {
        return {mInv.m[0][0] * n.x + mInv.m[1][0] * n.y + mInv.m[2][0] * n.z,
                mInv.m[0][1] * n.x + mInv.m[1][1] * n.y + mInv.m[2][1] * n.z,
                mInv.m[0][2] * n.x + mInv.m[1][2] * n.y + mInv.m[2][2] * n.z};
    }
    CA_HD bool swapsHandedness() const {
        Float det = m.m[0][0] * (m.m[1][1] * m.m[2][2] - m.m[1][2] * m.m[2][1]) -
                    m.m[0][1] * (m.m[1][0] * m.m[2][2] - m.m[1][2] * m.m[2][0]) +
                    m.m[0][2] * (m.m[1][0] * m.m[2][1] - m.m[1][1] * m.m[2][0]);
        return det < 0;
    }
};

// Builders (host only), following Mitsuba 3's conventions (angles in degrees).
Transform translate(Vec3f t);
Transform scale(Vec3f s);
Transform rotate(Vec3f axis, Float angleDegrees);
/// Mitsuba's lookat: camera +z towards target, +y along up, +x = cross(up, dir) (to the left).
Transform lookAt(Vec3f origin, Vec3f target, Vec3f up);

}  // namespace caustica
