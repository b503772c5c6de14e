// The angle between two normals as a shader sees them: the measure of a normal map's stored error in
// degrees for half and uint16 texels (worstAngleErrorDegrees). Block formats' decoded texels are measured
// by the same formulas two texels at a time (io/block_plan.cpp), which keeps to this one's operations.
#pragma once

#include <algorithm>
#include <cmath>

namespace heightpack {

inline constexpr double kDegreesPerRadian = 57.29577951308232;

// The unit normal whose x and y are given, z rebuilt as the shader does (x, y past the unit circle: on it).
inline void normalFromXy(double x, double y, double n[3]) {
    const double rr = x * x + y * y;
    if (rr <= 1.0) {
        n[0] = x, n[1] = y, n[2] = std::sqrt(1.0 - rr);
        return;
    }
    const double r = std::sqrt(rr);
    n[0] = x / r, n[1] = y / r, n[2] = 0.0;
}

// The unit vector along x, y, z, as a shader's normalize gives (zero stays zero).
inline void normalFromXyz(double x, double y, double z, double n[3]) {
    const double length = std::sqrt(x * x + y * y + z * z);
    const double inverse = length > 0.0 ? 1.0 / length : 0.0;
    n[0] = x * inverse, n[1] = y * inverse, n[2] = z * inverse;
}

// The angle between unit vectors a and b, 2 asin(|a - b| / 2): from the chord, which (unlike the dot
// product's acos) keeps its precision at small angles; the series for those is what makes a level's
// measurement cheap next to its encoding (|a - b| / 2 under 0.1: the next term is below 1e-11 radians).
inline double angleBetween(const double a[3], const double b[3]) {
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    const double h = 0.5 * std::sqrt(dx * dx + dy * dy + dz * dz);
    if (h >= 0.1) return 2.0 * std::asin(std::min(h, 1.0));
    const double h2 = h * h;
    return 2.0 * h * (1.0 + h2 * (1.0 / 6.0 + h2 * (3.0 / 40.0 + h2 * (15.0 / 336.0 + h2 * (105.0 / 3456.0)))));
}

}  // namespace heightpack
