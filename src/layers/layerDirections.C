#include "layerStars.H"

namespace pmsh
{

namespace
{

//- Tag of the layered triangles' sums; unlayered surfaces are tagged by
//  their region (>= 0), partition interfaces do not count.
constexpr label layeredTag = -1;

//- Unit direction d made to slide along unlayered surfaces of these unit
//  normals: in the plane of one, along the line where two meet.
vector3 slide(const vector3& d, const std::vector<vector3>& planes)
{
    if (planes.empty())
    {
        return d;
    }
    if (planes.size() > 1)
    {
        const vector3 line = normalised(cross(planes[0], planes[1]));
        if (magSqr(line) > 0)
        {
            return dot(d, line) >= 0 ? line : -1.0*line;
        }
    }
    return normalised(d - dot(d, planes[0])*planes[0]);
}


//- Triangle t's share of the normal at its point p, by Max's weights
//  (N. Max, J. Graphics Tools 4(2), 1999): cross(e1, e2)/(|e1|^2 |e2|^2)
//  for the edges from p, exact for points on a sphere, unlike angle or
//  area weights on triangles of uneven shape.
vector3 weightedNormal(const layerStars& stars, label t, label p)
{
    const triVerts f = stars.canonical(t);
    const auto& x = stars.surface().points;
    const int i = f[0] == p ? 0 : f[1] == p ? 1 : 2;
    const vector3 e1 = x[f[(i + 1) % 3]] - x[p];
    const vector3 e2 = x[f[(i + 2) % 3]] - x[p];
    return (1/(magSqr(e1)*magSqr(e2)))*cross(e1, e2);
}

} // End anonymous namespace


std::vector<vector3> layerDirections(const layerStars& stars)
{
    const auto normals = stars.sums
    (
        [&](label t, label p, label& tag, vector3& value)
        {
            if (stars.isInterface(t)) return false;
            tag = stars.specOf(t) ? layeredTag : stars.surface().region[t];
            value = weightedNormal(stars, t, p);
            return true;
        }
    );

    const label nPoints = normals.size();
    std::vector<vector3> direction(nPoints, vector3{0, 0, 0});
    for (label p = 0; p < nPoints; ++p)
    {
        if (normals[p].empty() || normals[p][0].first != layeredTag)
        {
            continue;
        }
        std::vector<vector3> planes;
        for (std::size_t i = 1; i < normals[p].size(); ++i)
        {
            planes.push_back(normalised(normals[p][i].second));
        }
        // Outward normals: the layers grow the other way
        direction[p] = slide(-1.0*normalised(normals[p][0].second), planes);
    }
    return direction;
}

} // End namespace pmsh
