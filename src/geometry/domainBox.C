/*---------------------------------------------------------------------------*\
  pmshFoam: the domain box of external flow (see domainBox.H).
\*---------------------------------------------------------------------------*/

#include "domainBox.H"
#include "domainCut.H"
#include "surfaceBuilder.H"
#include "surfaceTopology.H"
#include "pmshError.H"

#include "messageStream.H"

#include <algorithm>
#include <array>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace
{

//- s, bodies reaching the box's sides (sideReached, per side), replaced
//  by the box minus them; the log says which sides they reach and which
//  solids lay wholly outside.
void cutBodiesByBox
(
    pmsh::stlSurface& s,
    const pmsh::domainBox& box,
    const std::array<bool, 6>& sideReached,
    const std::string& what
)
{
    using namespace pmsh;
    domainCutReport report;
    stlSurface cut = boxMinusBodies
    (
        s, box.min, box.max, box.sideNames, box.plinthHeight, what, report
    );

    // Solids wholly outside the box leave no triangle: no patch either
    removeSolidsWithoutTriangles(cut);
    std::string sides, dropped;
    for (std::size_t side = 0; side < sideReached.size(); ++side)
    {
        if (sideReached[side])
        {
            sides += std::string(sides.empty() ? "" : ", ") + domainBox::sides[side];
        }
    }
    std::vector<bool> before(s.solidNames.size(), false);
    for (label solid : s.solid)
    {
        before[solid] = true;
    }
    for (std::size_t solid = 0; solid < s.solidNames.size(); ++solid)
    {
        const std::string& name = s.solidNames[solid];
        if
        (
            before[solid]
         && std::find(cut.solidNames.begin(), cut.solidNames.end(), name)
         == cut.solidNames.end()
        )
        {
            dropped += (dropped.empty() ? "" : ", ") + name;
        }
    }
    Foam::Info
        << "    bodies cut by the domain box: they reach its side(s) " << sides.c_str()
        << "; the fluid's surface is " << report.nTriangles << " triangles (CGAL"
        << " corefinement, " << report.seconds << " s)\n";
    if (report.nPlinths > 0)
    {
        Foam::Info
            << "        bodies standing on plinths: " << report.nPlinths << ", their parts"
            << " within plinthHeight " << box.plinthHeight << " of the sides they reach"
            << " replaced by their sections there, drawn out through the sides\n";
    }
    if (report.nPockets > 0)
    {
        const point3& at = report.pocketAt;
        Foam::Info
            << "        fluid closed off by the bodies and the sides, not meshed: "
            << report.nPockets << " pocket(s) of volume " << report.pocketVolume
            << " in all, the largest at (" << at[0] << ' ' << at[1] << ' ' << at[2]
            << ") (a body's cavity open only beyond a side)\n";
    }
    if (report.nNoPlinth > 0)
    {
        Foam::Info
            << "        bodies left without a plinth: " << report.nNoPlinth << " (each lies"
            << " within plinthHeight of a side, or its section there has a point on two"
            << " of its loops)\n";
    }
    if (!dropped.empty())
    {
        Foam::Info
            << "        solids wholly outside the box, not in the mesh: "
            << dropped.c_str() << "\n";
    }
    s = std::move(cut);
    orientShellsOutOfTheFluid(s);
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

void pmsh::putBodiesInDomain(stlSurface& s, const domainBox& box, const std::string& what)
{
    const char* function = "pmsh::putBodiesInDomain";
    const std::string boxText =
        "the domain box from " + str(box.min, 10) + " to " + str(box.max, 10);

    // No body wholly outside: a shell without a point strictly inside.
    // The sides a point lies on or beyond (xMin, xMax, ... as sides)
    std::array<bool, 6> sideReached{};
    const auto strictlyInside = [&](const point3& p)
    {
        bool inside = true;
        for (int side = 0; side < 6; ++side)
        {
            const int axis = side/2;
            const bool reached =
                side % 2 ? p[axis] >= box.max[axis] : p[axis] <= box.min[axis];
            sideReached[side] = sideReached[side] || reached;
            inside = inside && !reached;
        }
        return inside;
    };
    // Per shell (connected triangles): a point strictly inside, and the
    // first triangle, for the message
    label nShells = 0;
    const std::vector<label> shell = surfaceShells(label(s.points.size()), s.triangles, nShells);
    std::vector<bool> someInside(nShells, false);
    std::vector<label> firstTriangle(nShells, -1);
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        if (firstTriangle[shell[t]] < 0)
        {
            firstTriangle[shell[t]] = t;
        }
        for (label v : s.triangles[t])
        {
            const bool inside = strictlyInside(s.points[v]);
            someInside[shell[t]] = someInside[shell[t]] || inside;
        }
    }
    for (label sh = 0; sh < nShells; ++sh)
    {
        if (!someInside[sh])
        {
            const label t = firstTriangle[sh];
            const point3& p = s.points[s.triangles[t][0]];
            throw FatalError
            (
                msg() << "Solid " << s.solidNames[s.solid[t]] << " of " << what
                    << " lies outside " << boxText << ", at " << str(p, 10) << " for"
                    << " one.\nWith a domain every surface is a body in the flow: enlarge"
                    << " the box (min, max of 'domain' in system/pmshDict) or move the body",
                function
            );
        }
    }

    // The sides' patches, none a body's
    for (std::size_t side = 0; side < box.sideNames.size(); ++side)
    {
        const auto same =
            std::find(s.solidNames.begin(), s.solidNames.end(), box.sideNames[side]);
        if (same != s.solidNames.end())
        {
            throw FatalError
            (
                msg() << "The domain box's side " << domainBox::sides[side]
                    << " is patch '" << box.sideNames[side] << "', which is also a"
                    << " body's patch in " << what << ".\nName the side otherwise"
                    << " in 'patches' of 'domain' in system/pmshDict",
                function
            );
        }
    }

    if (std::find(sideReached.begin(), sideReached.end(), true) != sideReached.end())
    {
        cutBodiesByBox(s, box, sideReached, what);
        return;
    }

    // Two outward triangles a side
    surfaceBuilder builder(s, "");
    auto corner = [&](int i, int j, int k)
    {
        return point3{(i ? box.max : box.min)[0], (j ? box.max : box.min)[1],
                      (k ? box.max : box.min)[2]};
    };
    // Each side's corners in order round its outward normal
    const std::array<std::array<std::array<int, 3>, 4>, 6> quads
    {{
        {{{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}},     // xMin
        {{{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}},     // xMax
        {{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}},     // yMin
        {{{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}},     // yMax
        {{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}},     // zMin
        {{{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}}      // zMax
    }};
    for (std::size_t side = 0; side < quads.size(); ++side)
    {
        const label solid = builder.addSolid(box.sideNames[side]);
        std::array<point3, 4> c;
        for (int i = 0; i < 4; ++i)
        {
            c[i] = corner(quads[side][i][0], quads[side][i][1], quads[side][i][2]);
        }
        builder.addTriangle(c[0], c[1], c[2], solid);
        builder.addTriangle(c[0], c[2], c[3], solid);
    }

    // The bodies, inside the box now, into themselves (and what nests in
    // them as the nesting says)
    orientShellsOutOfTheFluid(s);
}


pmsh::surfaceWrapReport pmsh::wrapBodies
(
    stlSurface& s,
    const domainBox& box,
    const std::string& what
)
{
    surfaceWrapReport report;
    if (box.wrap == "off")
    {
        return report;
    }
    std::string reason = "wrap on in 'domain'";
    if (box.wrap == "auto")
    {
        try
        {
            checkStlTopology(s, what);
            return report;
        }
        catch (const FatalError& e)
        {
            // The check's first sentence: what is wrong and an example
            reason = e.message().substr(0, e.message().find('\n'));
        }
    }
    s = wrapSurface(s, box.wrapSize, box.wrapOffset, report);
    report.reason = reason;
    Foam::Info
        << "    wrapped the bodies: " << reason.c_str() << "\n"
        << "        CGAL alpha wrap, wrapSize " << box.wrapSize << ", wrapOffset "
        << box.wrapOffset << ": " << report.nTriangles << " triangles from "
        << report.nInputTriangles << " in " << report.seconds << " s, at most "
        << report.maxDistance << " from them; " << report.nTidied
        << " moved to a neighbouring patch (islands of the nearest CAD"
        << " triangle's patches)\n";
    if (report.nFeatureEdges > 0)
    {
        const point3& at = report.featureDistanceAt;
        Foam::Info
            << "        the bodies' " << report.nFeatureEdges << " feature edges (sharper than "
            << surfaceFeatureAngle << " degrees): the wrap at most "
            << report.featureDistance << " from them (" << report.featureDistance/box.wrapSize
            << " of wrapSize), at (" << at[0] << ' ' << at[1] << ' ' << at[2] << "); "
            << 100*report.featureShareWithinSize << " % of the points along them within wrapSize\n";
    }
    return report;
}


// ************************************************************************* //
