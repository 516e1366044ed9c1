#include "tetShape.H"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

double pmsh::tetAspectRatio
(
    const point3& a, const point3& b, const point3& c, const point3& d
)
{
    // Face area vectors, magnitudes summed component by component as
    // cellClosedness does (the orientation does not matter for them)
    const std::array<vector3, 4> area =
    {
        0.5*cross(c - a, b - a),
        0.5*cross(b - a, d - a),
        0.5*cross(d - a, c - a),
        0.5*cross(c - b, d - b)
    };
    vector3 sumMag{0, 0, 0};
    for (const vector3& s : area)
    {
        for (int k = 0; k < 3; ++k)
        {
            sumMag[k] += std::abs(s[k]);
        }
    }
    const double lo = std::min({sumMag[0], sumMag[1], sumMag[2]});
    const double hi = std::max({sumMag[0], sumMag[1], sumMag[2]});
    const double volume = tetVolume6(a, b, c, d)/6;
    if (!(volume > 0) || !(lo > 0))
    {
        return std::numeric_limits<double>::infinity();
    }
    const double hydraulic =
        (sumMag[0] + sumMag[1] + sumMag[2])/6/std::cbrt(volume*volume);
    return std::max(hi/lo, hydraulic);
}


pmsh::tetShapeRange pmsh::tetShapeRangeOf(const TetMesh& mesh)
{
    if (mesh.tets.empty())
    {
        return {};
    }
    // Between the outward normals of two faces the angle is 180 degrees
    // minus the dihedral angle at their common edge: track the extreme
    // cosines of the normals' angles, one acos each at the end
    double minCos = 1, maxCos = -1;
    double maxAspectRatio = 0;
    for (const tetVerts& c : mesh.tets)
    {
        std::array<vector3, 4> n;
        for (int k = 0; k < 4; ++k)
        {
            const triVerts f = tetFace(c, k);
            const point3& a = mesh.points[f[0]];
            n[k] = cross(mesh.points[f[1]] - a, mesh.points[f[2]] - a);
            const double m = std::sqrt(magSqr(n[k]));
            n[k] = (m > 0 ? 1/m : 0)*n[k];
        }
        for (int i = 0; i < 4; ++i)
        {
            for (int j = i + 1; j < 4; ++j)
            {
                const double cosine = dot(n[i], n[j]);
                minCos = std::min(minCos, cosine);
                maxCos = std::max(maxCos, cosine);
            }
        }
        maxAspectRatio = std::max
        (
            maxAspectRatio,
            tetAspectRatio
            (
                mesh.points[c[0]], mesh.points[c[1]],
                mesh.points[c[2]], mesh.points[c[3]]
            )
        );
    }
    const auto deg = [](double c) { return std::acos(std::min(1.0, std::max(-1.0, c)))*180/M_PI; };
    // Dihedral = 180 - angle(n_i, n_j): the largest cosine gives the
    // largest dihedral angle
    return {180 - deg(minCos), 180 - deg(maxCos), maxAspectRatio};
}
