// Area lights, emissive surfaces and the sun on the CPU (seed 000 §4.6, §4.7; seed 002 §4.7.2.5–
// §4.7.5, §4.8): light units (tbl:8, tbl:12, eq:12, eq:33) and the diffuse illuminance of sphere,
// disk, rectangle and tube lights. Plain functions of doubles: the reference that tests, tools and
// documentation use; the GPU shaders mirror them in float.
//
// Units: lengths in metres, luminous power in lm, luminance in cd/m² (nits), illuminance in lux,
// angles in radians. The *illuminance* functions below return, as the seed's listings do, the
// illuminance of a light of luminance 1 cd/m² — i.e. π × the form factor, in sr; multiply by the
// light's luminance to get lux. Pure functions, thread-safe.
#pragma once

#include <glm/vec3.hpp>

namespace rg::lighting {

// ---- Units (tbl:8, tbl:12, eq:12, eq:33) --------------------------------------------------------

// eq:33: luminance of a Lambertian emitter of area A sending Φ into its outer hemisphere,
// L = Φ / (A π).
double lambertianLuminance(double lumens, double emittingArea);

// tbl:12, lm → cd/m²: sphere Φ / (4 r² π²), disk Φ / (r² π²), tube Φ / ((2π r l + 4π r²) π)
// (a capsule: cylinder of length l plus two half-spheres), rectangle Φ / (π w h).
double sphereLuminanceFromLumens(double lumens, double radius);
double diskLuminanceFromLumens(double lumens, double radius);
double tubeLuminanceFromLumens(double lumens, double radius, double length);
double rectangleLuminanceFromLumens(double lumens, double width, double height);

enum class AreaShape { Sphere, Disk, Tube, Rectangle };
struct AreaLightShape {
    AreaShape shape = AreaShape::Sphere;
    double radius = 0.0;  // sphere, disk, tube
    double length = 0.0;  // tube (the cylinder part)
    double width = 0.0;   // rectangle
    double height = 0.0;  // rectangle
};

// tbl:8: area lights take luminous power (lm), luminance (cd/m²) or EV100; emissive surfaces take
// luminance or EV100.
enum class AreaUnit { Lumens, Nits, Ev100 };

// The luminance (cd/m²) an area light of the given shape and intensity emits: tbl:12 for lm, eq:12
// (via rg::lights::luminanceFromEv100, 2^(EV − 3)) for EV100, unchanged for nits. The shape's
// sizes must be positive where the unit is lm (checked).
double areaLightLuminance(const AreaLightShape& shape, double value, AreaUnit unit);

// An emissive surface's luminance (cd/m²) from nits or EV100 (tbl:8, eq:12). Lumens have no
// meaning for an emissive surface without its area and are refused (checked).
double emissiveLuminance(double value, AreaUnit unit);

// §4.7.1: a punctual light whose intensity is given in luminance is promoted to an area light of
// this radius (1 cm), the same size as eq:14's minimum distance.
inline constexpr double kPromotedPunctualRadius = 0.01;

// ---- Sphere lights (lst:7, lst:10) --------------------------------------------------------------

// lst:7, WITHOUT_CORRECT_HORIZON ("patch to a sphere, frontal", Quilez): π r² / max(r², d²) ·
// saturate(n·l). Exact only while the whole sphere is above the horizon. eq:38: with the sphere's
// tbl:12 luminance this is Φ / (4π d²) ⟨n·l⟩, the point light's illuminance (eq:19).
double sphereIlluminanceAboveHorizon(double radius, double sqrDist, double NdotL);

// lst:7, with horizon ("patch to a sphere, tilted"): exact for every orientation. cosBeta is the
// cosine between the normal and the direction to the centre (unclamped). distance > radius is
// assumed; closer points are treated as touching the sphere. The listing's last term reads
// atan(sin β + sqrt(1 − y²) / x); the product sin β · sqrt(1 − y²) / x (as lst:10 has it) is the
// correct one and is what is used. A sphere entirely below the horizon gives 0.
double sphereIlluminanceTilted(double radius, double distance, double cosBeta);

// lst:10: the merged sphere/disk form. cosTheta is the unclamped cosine between the normal and the
// direction to the light's centre; sinSigmaSqr = sin²σ of the half-angle σ the light subtends
// (sphere: r²/d²; disk facing the point: r²/(r² + d²)). Exact for a sphere, and for a disk that
// faces the shaded point; ≥ 0 and continuous in cosTheta.
double illuminanceSphereOrDisk(double cosTheta, double sinSigmaSqr);

// lst:10, sphere evaluation: cos θ clamped to ±0.999 and sin²σ to 0.9999 (edge cases, and the point
// must not enter the light).
double sphereIlluminance(double radius, double sqrDist, double cosTheta);  // 0 inside the sphere

// ---- Disk lights (lst:8, lst:9, lst:10) ---------------------------------------------------------

// lst:8, WITHOUT_CORRECT_HORIZON (Coombe): π saturate(n_light·−l) saturate(n·l) / (d²/r² + 1).
// cosLight = dot(planeNormal, −L), the cosine at the light. eq:39: with the tbl:12 luminance this is
// Φ / (π (d² + r²)) ⟨n·l⟩, close to the spot light's eq:21.
double diskIlluminanceAboveHorizon(double radius, double sqrDist, double NdotL, double cosLight);

// lst:8, with horizon (Howell's catalogue, a disk facing the point, "almost exact"), multiplied by
// π saturate(cosLight) for the disk's own orientation. cosTheta is unclamped; a disk entirely below
// the horizon gives 0 (the listing would take the square root of a negative number there).
double diskIlluminanceHorizon(double radius, double distance, double cosTheta, double cosLight);

// lst:10, disk evaluation: sin²σ = r² / (r² + max(r², d²)) (the point never gets closer than r),
// times saturate(cosLight) for the disk's orientation.
double diskIlluminance(double radius, double sqrDist, double cosTheta, double cosLight);

// lst:9: a disk light with a spot cone attenuates as a spot light placed behind it, at the apex of
// the cone of half-angle halfOuterAngle through the disk's rim: lightPos − spotDirection · r / tan
// (the seed writes "+ lightForward ·", its lightForward pointing back at the light, as in lst:4).
// spotDirection is the unit direction the light shines in.
glm::dvec3 diskVirtualPosition(const glm::dvec3& lightPos, const glm::dvec3& spotDirection,
                               double discRadius, double halfOuterAngle);

// ---- The sun (lst:6, eq:28) ---------------------------------------------------------------------

// eq:28: the artist gives the illuminance E⊥ (lux) on a surface facing the sun; a surface at n·D
// receives E⊥ saturate(n·D). (The diffuse part treats the sun as punctual, lst:6.)
double sunIlluminance(double illuminancePerpendicular, double NdotD);

// lst:6: the specular direction — the point of the sun's disk (angular radius, radians) closest to
// the reflection vector R: R itself when it hits the disk, else the nearest point on its rim. D is
// the unit direction towards the sun, R unit length.
glm::dvec3 sunSpecularDirection(const glm::dvec3& sunDirection, const glm::dvec3& R,
                                double angularRadius);

// The sun as a disk of angular radius σ: its solid angle 2π (1 − cos σ) (sr) and the luminance
// (cd/m²) that gives E⊥ on a facing surface, L = E⊥ / (π sin²σ) (lst:10, first branch).
double sunSolidAngle(double angularRadius);
double sunLuminance(double illuminancePerpendicular, double angularRadius);

// ---- Rectangle and tube lights (seed 002 §4.7.2.5, §4.7.2.6, §4.7.5) ---------------------------

// Solid angle (sr) of a rectangle of half extents a × b seen from distance h on its axis.
double rightPyramidSolidAngle(double dist, double halfWidth, double halfHeight);

// Solid angle (sr) of the quad p0 p1 p2 p3 (in order around it) seen from worldPos, by the angles
// between the planes through worldPos and its edges (Girard: Σ angles − 2π). No horizon handling.
double rectangleSolidAngle(const glm::dvec3& worldPos, const glm::dvec3& p0, const glm::dvec3& p1,
                           const glm::dvec3& p2, const glm::dvec3& p3);

// Rectangle light (seed 002 §4.7.2.5): structured sampling of the light's shape — solid angle times
// the mean of saturate(n·l) over the 4 corners and the centre; 0 behind the light's plane.
// lightLeft and lightUp are the unit axes of the rectangle (width along lightLeft), lightPlaneNormal
// the direction it emits into.
double rectangleIlluminance(const glm::dvec3& worldPos, const glm::dvec3& worldNormal,
                            const glm::dvec3& lightPos, const glm::dvec3& lightLeft,
                            const glm::dvec3& lightUp, const glm::dvec3& lightPlaneNormal,
                            double width, double height);

// Tube light (seed 002 §4.7.2.6), a capsule from p0 to p1 of the given radius: the cylinder as a
// rectangle facing the point (length × 2r, structured sampling as above) plus the two half-spheres as
// one sphere at the closest point of the segment (lst:7's formula without horizon).
double tubeIlluminance(const glm::dvec3& worldPos, const glm::dvec3& worldNormal,
                       const glm::dvec3& p0, const glm::dvec3& p1, double radius);

// Seed 002 §4.7.5: the specular dominant direction for area lights, normalize(lerp(N, R, 1 − roughness)).
glm::dvec3 getSpecularDominantDirArea(const glm::dvec3& N, const glm::dvec3& R, double roughness);

}  // namespace rg::lighting
