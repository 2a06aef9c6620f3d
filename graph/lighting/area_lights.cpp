#include "area_lights.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/check.h"
#include "core/light_units.h"

namespace rg::lighting {

namespace {

constexpr double kPi = 3.14159265358979323846;

double saturate(double x) { return std::clamp(x, 0.0, 1.0); }

}  // namespace

double lambertianLuminance(double lumens, double emittingArea) {
    RG_CHECK(emittingArea > 0.0) << "a Lambertian emitter needs a positive area, got "
                                 << emittingArea;
    return lumens / (emittingArea * kPi);  // seed 000 eq:33
}

// seed 000 tbl:12. Sphere and disk are written as the table prints them; the tube and the rectangle
// through eq:33 with their emitting area (2π r l + 4π r², w h) — the same expressions.
double sphereLuminanceFromLumens(double lumens, double radius) {
    RG_CHECK(radius > 0.0) << "sphere light radius must be positive, got " << radius;
    return lumens / (4.0 * radius * radius * kPi * kPi);
}

double diskLuminanceFromLumens(double lumens, double radius) {
    RG_CHECK(radius > 0.0) << "disk light radius must be positive, got " << radius;
    return lumens / (radius * radius * kPi * kPi);
}

double tubeLuminanceFromLumens(double lumens, double radius, double length) {
    RG_CHECK(radius > 0.0 && length >= 0.0)
        << "tube light needs radius > 0 and length >= 0, got " << radius << ", " << length;
    return lumens / ((2.0 * kPi * radius * length + 4.0 * kPi * radius * radius) * kPi);
}

double rectangleLuminanceFromLumens(double lumens, double width, double height) {
    RG_CHECK(width > 0.0 && height > 0.0)
        << "rectangle light needs a positive size, got " << width << " x " << height;
    return lumens / (kPi * width * height);
}

double areaLightLuminance(const AreaLightShape& shape, double value, AreaUnit unit) {
    switch (unit) {
        case AreaUnit::Nits:
            return value;
        case AreaUnit::Ev100:
            return lights::luminanceFromEv100(value);  // eq:12
        case AreaUnit::Lumens:
            break;
    }
    switch (shape.shape) {
        case AreaShape::Sphere:
            return sphereLuminanceFromLumens(value, shape.radius);
        case AreaShape::Disk:
            return diskLuminanceFromLumens(value, shape.radius);
        case AreaShape::Tube:
            return tubeLuminanceFromLumens(value, shape.radius, shape.length);
        case AreaShape::Rectangle:
            return rectangleLuminanceFromLumens(value, shape.width, shape.height);
    }
    RG_CHECK(false) << "unknown area light shape " << static_cast<int>(shape.shape);
    return 0.0;
}

double emissiveLuminance(double value, AreaUnit unit) {
    RG_CHECK(unit != AreaUnit::Lumens)
        << "emissive surfaces take nits or EV100 (tbl:8), not lumens";
    return unit == AreaUnit::Ev100 ? lights::luminanceFromEv100(value) : value;  // eq:12
}

double sphereIlluminanceAboveHorizon(double radius, double sqrDist, double NdotL) {
    // seed 000 lst:7 (WITHOUT_CORRECT_HORIZON): "π ·" cancels the form factor's 1/π; max() keeps the
    // point out of the light.
    const double sqrLightRadius = radius * radius;
    return kPi * (sqrLightRadius / std::max(sqrLightRadius, sqrDist)) * saturate(NdotL);
}

double sphereIlluminanceTilted(double radius, double distance, double cosBeta) {
    // seed 000 lst:7 (with horizon): the "patch to a tilted sphere" form factor.
    const double c = std::clamp(cosBeta, -1.0, 1.0);
    const double beta = std::acos(c);
    const double h = std::max(distance / radius, 1.0 + 1e-9);
    if (h * c > 1.0) return kPi * c / (h * h);  // the whole sphere above the horizon
    if (h * c < -1.0) return 0.0;               // the whole sphere below it
    const double x = std::sqrt(h * h - 1.0);
    const double sinBeta = std::sin(beta);
    const double y = -x * (c / sinBeta);  // −x cot β; |y| ≤ 1 in this branch (sin β > 0 here)
    const double sqrtY = std::sqrt(std::max(0.0, 1.0 - y * y));
    const double formFactor =
        (1.0 / (kPi * h * h)) * (c * std::acos(std::clamp(y, -1.0, 1.0)) - x * sinBeta * sqrtY) +
        (1.0 / kPi) * std::atan(sinBeta * sqrtY / x);
    return kPi * formFactor;
}

double illuminanceSphereOrDisk(double cosTheta, double sinSigmaSqr) {
    // seed 000 lst:10. The solid angle of both is 2π (1 − cos σ); three phases of the curve: the light
    // fully above the horizon (cos²θ > sin²σ and cos θ > 0: π sin²σ cos θ), crossing it, fully
    // below (0) — the first and last folded into one test with saturate(cos θ).
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    double illuminance = 0.0;
    if (cosTheta * cosTheta > sinSigmaSqr) {
        illuminance = kPi * sinSigmaSqr * saturate(cosTheta);
    } else {
        const double x = std::sqrt(1.0 / sinSigmaSqr - 1.0);  // d / r for the disk
        const double y = -x * (cosTheta / sinTheta);
        const double sinThetaSqrtY = sinTheta * std::sqrt(std::max(0.0, 1.0 - y * y));
        illuminance =
            (cosTheta * std::acos(std::clamp(y, -1.0, 1.0)) - x * sinThetaSqrtY) * sinSigmaSqr +
            std::atan(sinThetaSqrtY / x);
    }
    return std::max(illuminance, 0.0);
}

double sphereIlluminance(double radius, double sqrDist, double cosTheta) {
    // A point inside the sphere gets nothing: its surface emits outwards (as lighting.glsl and the
    // reference mode).
    if (sqrDist < radius * radius) return 0.0;
    // seed 000 lst:10, sphere evaluation: clamps avoid the edge cases.
    const double c = std::clamp(cosTheta, -0.999, 0.999);
    const double sinSigmaSqr = std::min(radius * radius / sqrDist, 0.9999);
    return illuminanceSphereOrDisk(c, sinSigmaSqr);
}

double diskIlluminanceAboveHorizon(double radius, double sqrDist, double NdotL, double cosLight) {
    // seed 000 lst:8 (WITHOUT_CORRECT_HORIZON), Coombe's form factor times π.
    return kPi * saturate(cosLight) * saturate(NdotL) / (sqrDist / (radius * radius) + 1.0);
}

double diskIlluminanceHorizon(double radius, double distance, double cosTheta, double cosLight) {
    // seed 000 lst:8 (with horizon): a disk facing the point, tilted receiver (Howell's catalogue).
    const double c = std::clamp(cosTheta, -1.0, 1.0);
    const double theta = std::acos(c);
    const double H = distance / radius;
    const double H2 = H * H;
    double illuminance = 0.0;
    if (theta < std::atan(H)) {  // acot(1/H): the whole disk above the horizon
        illuminance = (1.0 / (1.0 + H2)) * c;
    } else if (theta < kPi - std::atan(H)) {  // beyond it the disk is entirely below the horizon
        const double cotTheta = c / std::sin(theta);
        const double X = std::sqrt(std::max(0.0, 1.0 - H2 * cotTheta * cotTheta));
        const double sinTheta = std::sin(theta);
        illuminance =
            -H * X * sinTheta / (kPi * (1.0 + H2)) + (1.0 / kPi) * std::atan(X * sinTheta / H) +
            c * (kPi - std::acos(std::clamp(H * cotTheta, -1.0, 1.0))) / (kPi * (1.0 + H2));
    }
    // The listing's closing multiplication: π for the form factor, the disk's orientation as a cosine.
    return std::max(illuminance, 0.0) * kPi * saturate(cosLight);
}

double diskIlluminance(double radius, double sqrDist, double cosTheta, double cosLight) {
    // seed 000 lst:10, disk evaluation.
    const double sqrLightRadius = radius * radius;
    const double sinSigmaSqr =
        sqrLightRadius / (sqrLightRadius + std::max(sqrLightRadius, sqrDist));
    return illuminanceSphereOrDisk(cosTheta, sinSigmaSqr) * saturate(cosLight);
}

glm::dvec3 diskVirtualPosition(const glm::dvec3& lightPos, const glm::dvec3& spotDirection,
                               double discRadius, double halfOuterAngle) {
    // seed 000 lst:9: the apex of the cone of half-angle θ_outer through the disk's rim.
    return lightPos - spotDirection * (discRadius / std::tan(halfOuterAngle));
}

double sunIlluminance(double illuminancePerpendicular, double NdotD) {
    return illuminancePerpendicular * saturate(NdotD);  // seed 000 eq:28, lst:6
}

glm::dvec3 sunSpecularDirection(const glm::dvec3& sunDirection, const glm::dvec3& R,
                                double angularRadius) {
    // seed 000 lst:6: the disk of radius sin σ at distance cos σ along D; the closest point to R (a
    // good approximation because the sun is small).
    const double r = std::sin(angularRadius);
    const double d = std::cos(angularRadius);
    const double DdotR = glm::dot(sunDirection, R);
    const glm::dvec3 S = R - DdotR * sunDirection;
    return DdotR < d ? glm::normalize(d * sunDirection + glm::normalize(S) * r) : R;
}

double sunSolidAngle(double angularRadius) { return 2.0 * kPi * (1.0 - std::cos(angularRadius)); }

double sunLuminance(double illuminancePerpendicular, double angularRadius) {
    // lst:10, first branch at cos θ = 1: E⊥ = π L sin²σ.
    const double s = std::sin(angularRadius);
    return illuminancePerpendicular / (kPi * s * s);
}

double rightPyramidSolidAngle(double dist, double halfWidth, double halfHeight) {
    // seed 002 §4.7.2.5, rightPyramidSolidAngle.
    const double a = halfWidth, b = halfHeight, h = dist;
    return 4.0 * std::asin(a * b / std::sqrt((a * a + h * h) * (b * b + h * h)));
}

double rectangleSolidAngle(const glm::dvec3& worldPos, const glm::dvec3& p0, const glm::dvec3& p1,
                           const glm::dvec3& p2, const glm::dvec3& p3) {
    // seed 002 §4.7.2.5, rectangleSolidAngle: the spherical quad's area from its angles.
    const glm::dvec3 v0 = p0 - worldPos, v1 = p1 - worldPos, v2 = p2 - worldPos, v3 = p3 - worldPos;
    const glm::dvec3 n0 = glm::normalize(glm::cross(v0, v1));
    const glm::dvec3 n1 = glm::normalize(glm::cross(v1, v2));
    const glm::dvec3 n2 = glm::normalize(glm::cross(v2, v3));
    const glm::dvec3 n3 = glm::normalize(glm::cross(v3, v0));
    const auto angle = [](const glm::dvec3& a, const glm::dvec3& b) {
        return std::acos(std::clamp(glm::dot(-a, b), -1.0, 1.0));
    };
    return angle(n0, n1) + angle(n1, n2) + angle(n2, n3) + angle(n3, n0) - 2.0 * kPi;
}

namespace {

// seed 002 §4.7.2.5: Ω · mean of saturate(n·l) over the corners and the centre (structured sampling).
double structuredQuadIlluminance(const glm::dvec3& worldPos, const glm::dvec3& worldNormal,
                                 const glm::dvec3& center, const glm::dvec3& p0,
                                 const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3) {
    const double solidAngle = rectangleSolidAngle(worldPos, p0, p1, p2, p3);
    const auto cosine = [&](const glm::dvec3& p) {
        return saturate(glm::dot(glm::normalize(p - worldPos), worldNormal));
    };
    return solidAngle * 0.2 * (cosine(p0) + cosine(p1) + cosine(p2) + cosine(p3) + cosine(center));
}

}  // namespace

double rectangleIlluminance(const glm::dvec3& worldPos, const glm::dvec3& worldNormal,
                            const glm::dvec3& lightPos, const glm::dvec3& lightLeft,
                            const glm::dvec3& lightUp, const glm::dvec3& lightPlaneNormal,
                            double width, double height) {
    if (glm::dot(worldPos - lightPos, lightPlaneNormal) <= 0.0)
        return 0.0;  // behind a one-sided emitter
    const double halfWidth = width * 0.5, halfHeight = height * 0.5;
    const glm::dvec3 p0 = lightPos + lightLeft * -halfWidth + lightUp * halfHeight;
    const glm::dvec3 p1 = lightPos + lightLeft * -halfWidth + lightUp * -halfHeight;
    const glm::dvec3 p2 = lightPos + lightLeft * halfWidth + lightUp * -halfHeight;
    const glm::dvec3 p3 = lightPos + lightLeft * halfWidth + lightUp * halfHeight;
    return structuredQuadIlluminance(worldPos, worldNormal, lightPos, p0, p1, p2, p3);
}

double tubeIlluminance(const glm::dvec3& worldPos, const glm::dvec3& worldNormal,
                       const glm::dvec3& p0, const glm::dvec3& p1, double radius) {
    // seed 002 §4.7.2.6: the capsule split into a cylinder (a rectangle facing the point) and two
    // half-spheres (one sphere at the segment's closest point).
    const glm::dvec3 ab = p1 - p0;
    const double lengthSq = glm::dot(ab, ab);
    RG_CHECK(lengthSq > 0.0) << "a tube light needs two distinct end points";
    const double t = glm::dot(worldPos - p0, ab) / lengthSq;
    const glm::dvec3 closestOnLine = p0 + t * ab;
    const glm::dvec3 closestOnSegment = p0 + std::clamp(t, 0.0, 1.0) * ab;
    // Inside the capsule: nothing (it emits outwards), as lighting.glsl and the reference mode.
    if (glm::dot(closestOnSegment - worldPos, closestOnSegment - worldPos) < radius * radius)
        return 0.0;
    const glm::dvec3 lightPos = 0.5 * (p0 + p1);
    const double lightWidth = std::sqrt(lengthSq);
    const glm::dvec3 left = ab / lightWidth;
    const glm::dvec3 forward = glm::normalize(closestOnLine - worldPos);
    const glm::dvec3 up = glm::cross(left, forward);
    const glm::dvec3 q0 = lightPos - left * (0.5 * lightWidth) + radius * up;
    const glm::dvec3 q1 = lightPos - left * (0.5 * lightWidth) - radius * up;
    const glm::dvec3 q2 = lightPos + left * (0.5 * lightWidth) - radius * up;
    const glm::dvec3 q3 = lightPos + left * (0.5 * lightWidth) + radius * up;
    double illuminance = structuredQuadIlluminance(worldPos, worldNormal, lightPos, q0, q1, q2, q3);

    const glm::dvec3 sphereUnormL = closestOnSegment - worldPos;
    const double sqrSphereDistance = glm::dot(sphereUnormL, sphereUnormL);
    const glm::dvec3 sphereL = sphereUnormL / std::sqrt(sqrSphereDistance);
    illuminance +=
        kPi * saturate(glm::dot(sphereL, worldNormal)) * (radius * radius / sqrSphereDistance);
    return illuminance;
}

glm::dvec3 getSpecularDominantDirArea(const glm::dvec3& N, const glm::dvec3& R, double roughness) {
    const double lerpFactor = 1.0 - roughness;  // seed 002 §4.7.5, a simple linear approximation
    return glm::normalize(N + (R - N) * lerpFactor);
}

}  // namespace rg::lighting
