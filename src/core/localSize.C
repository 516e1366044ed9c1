#include "localSize.H"

#include <algorithm>
#include <cmath>

// * * * * * * * * * * * * * * * * sizeRegion  * * * * * * * * * * * * * * //

std::vector<std::string> pmsh::sizeRegion::shapeNames()
{
    return {"box", "sphere", "cylinder"};
}


const char* pmsh::sizeRegion::shapeName() const
{
    switch (type)
    {
        case shape::sphere: return "sphere";
        case shape::cylinder: return "cylinder";
        default: return "box";
    }
}


bool pmsh::sizeRegion::contains(const point3& p) const
{
    switch (type)
    {
        case shape::sphere:
            return magSqr(p - centre) <= radius*radius;

        case shape::cylinder:
        {
            const vector3 axis = point2 - point1;
            const double t = dot(p - point1, axis)/magSqr(axis);
            if (t < 0 || t > 1)
            {
                return false;
            }
            return magSqr(p - (point1 + t*axis)) <= radius*radius;
        }

        default:
            for (int k = 0; k < 3; ++k)
            {
                if (p[k] < min[k] || p[k] > max[k])
                {
                    return false;
                }
            }
            return true;
    }
}


void pmsh::sizeRegion::bounds(point3& lo, point3& hi) const
{
    switch (type)
    {
        case shape::sphere:
            for (int k = 0; k < 3; ++k)
            {
                lo[k] = centre[k] - radius;
                hi[k] = centre[k] + radius;
            }
            break;

        case shape::cylinder:
            // The end discs reach at most radius beyond the axis ends
            for (int k = 0; k < 3; ++k)
            {
                lo[k] = std::min(point1[k], point2[k]) - radius;
                hi[k] = std::max(point1[k], point2[k]) + radius;
            }
            break;

        default:
            lo = min;
            hi = max;
    }
}


double pmsh::sizeRegion::volume() const
{
    const double pi = 3.14159265358979323846;
    switch (type)
    {
        case shape::sphere:
            return 4.0/3.0*pi*radius*radius*radius;

        case shape::cylinder:
            return pi*radius*radius*std::sqrt(magSqr(point2 - point1));

        default:
            return (max[0] - min[0])*(max[1] - min[1])*(max[2] - min[2]);
    }
}


pmsh::sizeRegion pmsh::sizeRegion::scaled(double factor) const
{
    sizeRegion r = *this;
    r.size /= factor;
    return r;
}


// * * * * * * * * * * * * * * * * Sampling  * * * * * * * * * * * * * * * //

double pmsh::regionSizeAt
(
    const std::vector<sizeRegion>& regions,
    const point3& p,
    double largest
)
{
    double size = largest;
    for (const sizeRegion& r : regions)
    {
        if (r.size < size && r.contains(p))
        {
            size = r.size;
        }
    }
    return size;
}


std::size_t pmsh::forEachSample
(
    const sizeRegion& region,
    const point3& lo,
    const point3& hi,
    const std::function<void(const point3&)>& visit
)
{
    point3 rlo, rhi;
    region.bounds(rlo, rhi);

    // Grid lines of the whole shape, centred in its bounds (so that thin
    // shapes get a sample on their mid-plane), clipped to [lo, hi]
    std::array<long, 3> first{}, last{};
    point3 start{};
    const double h = region.size;
    for (int k = 0; k < 3; ++k)
    {
        const long n = long(std::ceil((rhi[k] - rlo[k])/h));
        start[k] = 0.5*(rlo[k] + rhi[k]) - 0.5*n*h;
        first[k] = std::max(0L, long(std::floor((lo[k] - start[k])/h)));
        last[k] = std::min(n, long(std::ceil((hi[k] - start[k])/h)));
        if (last[k] < first[k])
        {
            return 0;
        }
    }

    std::size_t nVisited = 0;
    for (long i = first[0]; i <= last[0]; ++i)
    {
        for (long j = first[1]; j <= last[1]; ++j)
        {
            for (long k = first[2]; k <= last[2]; ++k)
            {
                const point3 p
                {
                    start[0] + i*h, start[1] + j*h, start[2] + k*h
                };
                if (region.contains(p))
                {
                    visit(p);
                    ++nVisited;
                }
            }
        }
    }
    return nVisited;
}


void pmsh::sampleTriangle
(
    const point3& a,
    const point3& b,
    const point3& c,
    double size,
    const std::function<void(const point3&)>& visit
)
{
    const double longest = std::sqrt
    (
        std::max({magSqr(b - a), magSqr(c - b), magSqr(a - c)})
    );
    const int n = std::max(1, int(std::ceil(longest/size)));
    for (int i = 0; i <= n; ++i)
    {
        for (int j = 0; i + j <= n; ++j)
        {
            const double u = double(i)/n;
            const double v = double(j)/n;
            visit((1 - u - v)*a + u*b + v*c);
        }
    }
}


// ************************************************************************* //
