/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen CSG geometry (Netgen itself is behind netgenInterface).
\*---------------------------------------------------------------------------*/

#include "csgGeometry.H"
#include "netgenInterface.H"
#include "pmshError.H"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <set>

// * * * * * * * * * * * * * * * Local helpers  * * * * * * * * * * * * * * //

namespace
{

//- Open the model. Netgen reports an undefined top-level object ("tlo x;")
//  only after reading past it, with the line of the next token (often one
//  past the end of the file): give the line of the tlo and the solids
//  that are defined instead.
pmsh::ng::csgModel* openModel(const std::string& fileName)
{
    try
    {
        return new pmsh::ng::csgModel(fileName);
    }
    catch (const pmsh::FatalError& e)
    {
        std::smatch undefined;
        const std::string message = e.message();
        if
        (
           !std::regex_search
            (
                message, undefined,
                std::regex("Parsing error in line [0-9]+: Top-Level-Object"
                           " (\\S+) not defined")
            )
        )
        {
            throw;
        }
        const std::string name = undefined[1];

        std::ifstream is(fileName);
        std::string quoted;
        for (char c : name)
        {
            if (std::string("^$\\.*+?()[]{}|").find(c) != std::string::npos)
            {
                quoted += '\\';
            }
            quoted += c;
        }
        const std::regex tlo("^\\s*tlo\\s+" + quoted + "(\\s|;|$)");
        const std::regex solid("^\\s*solid\\s+([A-Za-z_][A-Za-z0-9_]*)\\s*=");
        int tloLine = 0;
        int lineNo = 0;
        std::string solids;
        for (std::string line; std::getline(is, line); )
        {
            ++lineNo;
            std::smatch m;
            if (!tloLine && std::regex_search(line, tlo))
            {
                tloLine = lineNo;
            }
            if (std::regex_search(line, m, solid))
            {
                solids += (solids.empty() ? "" : ", ") + m[1].str();
            }
        }
        std::string where = message.substr(0, undefined.position(0));
        if (tloLine)
        {
            where += "Parsing error in line " + std::to_string(tloLine) + ": ";
        }
        else
        {
            where += undefined.str(0).substr(0, undefined.str(0).find(':') + 2);
        }
        throw pmsh::FatalError
        (
            pmsh::msg()
                << where << "top-level object (tlo) " << name
                << " is not a solid defined before it\n"
                << "Defined solids: "
                << (solids.empty() ? std::string("none") : solids),
            e.where()
        );
    }
}

//- Why a periodic identification cannot become a pair of cyclic patches
//  (the caller names the file and the statement)
struct periodicProblem
{
    std::string why;
};


//- The patch pair of one periodic identification, whose point pairs are
//  `image` (a point of the first surface to its image): every boundary
//  face whose points all have images has its image on the boundary, all
//  those faces make one patch, their images another, and nothing else is
//  in either. Separation not set.
pmsh::periodicPatchPair patchPairOf
(
    const pmsh::CoarseMesh& coarse,
    const std::map<pmsh::triVerts, pmsh::label>& faceOf,
    const std::map<pmsh::label, pmsh::label>& image
)
{
    using namespace pmsh;
    std::map<std::pair<label, label>, label> patchPairs;
    for (const coarseBoundaryFace& b : coarse.boundary)
    {
        triVerts f;
        bool mapped = true;
        for (int k = 0; k < 3 && mapped; ++k)
        {
            const auto it = image.find(b.v[k]);
            mapped = it != image.end();
            f[k] = mapped ? it->second : -1;
        }
        if (!mapped)
        {
            continue;
        }
        std::sort(f.begin(), f.end());
        const auto it = faceOf.find(f);
        if (it == faceOf.end())
        {
            throw periodicProblem
            {
                "a face of patch " + coarse.patches[b.patch].name
              + " has no image on the boundary. The two surfaces must be"
                " the same shape, one a translation of the other"
            };
        }
        const label other = coarse.boundary[it->second].patch;
        if (other == b.patch)
        {
            throw periodicProblem
            {
                "both surfaces are in patch " + coarse.patches[b.patch].name
              + ". Give each its own -bcname"
            };
        }
        ++patchPairs[{b.patch, other}];
    }
    if (patchPairs.empty())
    {
        throw periodicProblem
        {
            "none of its faces is on the boundary with its image. Both"
            " surfaces must bound the meshed solids (not lie between two"
            " of them), one a translation of the other"
        };
    }
    if (patchPairs.size() > 1)
    {
        std::string names;
        for (const auto& [pp, n] : patchPairs)
        {
            names += (names.empty() ? "" : ", ") + coarse.patches[pp.first].name
              + " -> " + coarse.patches[pp.second].name;
        }
        throw periodicProblem
        {
            "its faces and their images are in several pairs of patches ("
          + names + "). Give each of its two surfaces its own -bcname"
        };
    }

    const auto& [pp, nFaces] = *patchPairs.begin();
    for (const label patch : {pp.first, pp.second})
    {
        label nPatchFaces = 0;
        for (const coarseBoundaryFace& b : coarse.boundary)
        {
            nPatchFaces += b.patch == patch;
        }
        if (nPatchFaces != nFaces)
        {
            throw periodicProblem
            {
                "patch " + coarse.patches[patch].name + " has "
              + std::to_string(nPatchFaces) + " faces, of which "
              + std::to_string(nFaces) + " are paired with patch "
              + coarse.patches[patch == pp.first ? pp.second : pp.first].name
              + "'s. Give each periodic surface its own -bcname, and"
                " nothing else that name"
            };
        }
    }
    return {pp.first, pp.second, {0, 0, 0}};
}


//- The translation that takes every point of `image` to its image: the
//  same nonzero vector for all (a rotation's images move by different
//  vectors; points where the two surfaces meet, e.g. a wedge's axis, are
//  their own images)
pmsh::vector3 translationOf
(
    const pmsh::CoarseMesh& coarse,
    const std::map<pmsh::label, pmsh::label>& image,
    const std::string& firstSolid,
    const std::string& secondSolid
)
{
    using namespace pmsh;
    double size = 1;
    for (const point3& p : coarse.points)
    {
        size = std::max(size, std::sqrt(magSqr(p)));
    }
    const double tolerance = 1e-9*size;
    const vector3 separation =
        coarse.points[image.begin()->second] - coarse.points[image.begin()->first];
    bool translation = std::sqrt(magSqr(separation)) > tolerance;
    for (const auto& [point, imagePoint] : image)
    {
        const vector3 d = coarse.points[imagePoint] - coarse.points[point];
        translation = translation && std::sqrt(magSqr(d - separation)) <= tolerance;
    }
    if (!translation)
    {
        throw periodicProblem
        {
            firstSolid + " and " + secondSolid + " are not a translation of"
            " each other (Netgen's images of their points do not all move by"
            " one vector). Only translational periodic pairs are supported,"
            " not rotational ones (e.g. the two sides of a wedge)"
        };
    }
    return separation;
}


} // End anonymous namespace


// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace pmsh
{
    // Netgen CSG files (algebraic3d)
    addNamedToRunTimeSelectionTable(Geometry, csgGeometry, extension, geo);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

pmsh::csgGeometry::csgGeometry(const std::string& fileName)
:
    fileName_(fileName),
    model_(openModel(fileName))
{}


pmsh::csgGeometry::~csgGeometry() = default;


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

pmsh::label pmsh::csgGeometry::nSurfaces() const
{
    return model_->nSurfaces();
}


pmsh::CoarseMesh pmsh::csgGeometry::netgenMesh
(
    const coarseMeshParameters& parameters,
    bool surfaceOnly
) const
{
    if (!(parameters.maxCellSize > 0))
    {
        throw FatalError
        (
            msg()
                << "maxCellSize " << parameters.maxCellSize << " for CSG"
                << " geometry \"" << fileName_ << "\" must be positive",
            "pmsh::csgGeometry::netgenMesh"
        );
    }

    ng::meshParameters mp;
    mp.maxh = parameters.maxCellSize;
    mp.grading = parameters.grading;
    mp.surfaceOnly = surfaceOnly;
    mp.regions = parameters.regions;
    mp.sizePoints = parameters.sizePoints;
    ng::volumeMesh m = model_->generateMesh(mp);

    // Patch name of each bc number: Netgen's bcname, else the name of the
    // top-level solid it bounds, so that the surfaces of one solid without
    // a bcname share one patch ("default" is Netgen's name for "none
    // given"; patch<bc> only if the solid has no name either)
    // A side of a periodic pair without a bcname is named after its solid
    // as 'identify periodic' names it: each side needs a patch of its own
    std::map<label, label> bcDomain;
    std::map<label, std::set<label>> bcSurfaces;
    for (const ng::boundaryTriangle& b : m.boundary)
    {
        bcDomain.emplace(b.bc, b.domain);
        if (!m.periodic.empty())
        {
            bcSurfaces[b.bc].insert(b.surface);
        }
    }
    std::map<label, std::string> periodicSolid;
    for (const ng::periodicIdentification& p : m.periodic)
    {
        periodicSolid[p.firstSurface] = p.firstSolid;
        periodicSolid[p.secondSurface] = p.secondSolid;
    }
    std::map<label, std::string> bcPatchName;
    for (const auto& [bc, name] : m.bcNames)
    {
        const std::set<label>& surfaces = bcSurfaces[bc];
        const auto periodic =
            surfaces.size() == 1
          ? periodicSolid.find(*surfaces.begin()) : periodicSolid.end();
        const std::string& solid = m.domainNames[bcDomain[bc]];
        bcPatchName[bc] =
            !name.empty() && name != "default" ? name
          : periodic != periodicSolid.end() && !periodic->second.empty()
          ? periodic->second
          : !solid.empty() ? solid
          : "patch" + std::to_string(bc);
    }

    // One patch per name, ordered by the smallest bc number with that name
    // (the map iterates bc numbers in increasing order)
    CoarseMesh coarse;
    std::map<std::string, label> nameIndex;
    std::map<label, label> bcPatch;
    for (const auto& bp : bcPatchName)
    {
        auto it = nameIndex.find(bp.second);
        if (it == nameIndex.end())
        {
            it = nameIndex.emplace(bp.second, label(coarse.patches.size())).first;
            coarse.patches.push_back({bp.second});
        }
        bcPatch[bp.first] = it->second;
    }

    // One zone per top-level solid that has cells or bounds a surface,
    // in Netgen's domain order, named after its solid; none for one region
    std::map<label, label> domainZone;
    for (const auto& dn : m.domainNames)
    {
        domainZone.emplace(dn.first, label(domainZone.size()));
    }
    if (domainZone.size() > 1)
    {
        for (const auto& [domain, name] : m.domainNames)
        {
            std::string zone = name.empty() ? "region" + std::to_string(domain) : name;
            // Two tlo of one solid: keep the names apart
            while
            (
                std::find(coarse.zones.begin(), coarse.zones.end(), zone)
             != coarse.zones.end()
            )
            {
                zone += "_" + std::to_string(domain);
            }
            coarse.zones.push_back(zone);
        }
        coarse.cellZone.reserve(m.tetDomain.size());
        for (label d : m.tetDomain)
        {
            coarse.cellZone.push_back(domainZone.at(d));
        }
    }
    auto zoneOf = [&](label domain)
    {
        return coarse.zones.empty() ? 0 : domainZone.at(domain);
    };

    coarse.points = std::move(m.points);
    coarse.tets = std::move(m.tets);
    coarse.boundary.reserve(m.boundary.size());
    for (const ng::boundaryTriangle& b : m.boundary)
    {
        coarse.boundary.push_back({b.v, bcPatch.at(b.bc), b.surface, zoneOf(b.domain)});
    }
    if (!coarse.zones.empty())
    {
        for (const ng::boundaryTriangle& b : m.interfaces)
        {
            coarse.zoneFaces.push_back
            (
                {b.v, b.surface, zoneOf(b.domain), zoneOf(b.otherDomain)}
            );
        }
    }
    else if (!m.interfaces.empty())
    {
        throw FatalError
        (
            msg()
                << "CSG geometry \"" << fileName_ << "\": Netgen gave "
                << m.interfaces.size() << " triangles between two domains"
                << " of a geometry with one top-level solid",
            "pmsh::csgGeometry::netgenMesh"
        );
    }
    setPeriodicPatches(coarse, m.periodic);
    return coarse;
}


void pmsh::csgGeometry::setPeriodicPatches
(
    CoarseMesh& coarse,
    const std::vector<ng::periodicIdentification>& identifications
) const
{
    if (identifications.empty())
    {
        return;
    }
    std::map<triVerts, label> faceOf;
    for (std::size_t b = 0; b < coarse.boundary.size(); ++b)
    {
        triVerts f = coarse.boundary[b].v;
        std::sort(f.begin(), f.end());
        faceOf[f] = label(b);
    }

    // Faces per surface: on the boundary, and between two regions
    std::map<label, label> nBoundaryFaces;
    std::map<label, label> nZoneFaces;
    for (const coarseBoundaryFace& b : coarse.boundary)
    {
        ++nBoundaryFaces[b.surface];
    }
    for (const coarseZoneFace& z : coarse.zoneFaces)
    {
        ++nZoneFaces[z.surface];
    }

    std::vector<std::string> pairedBy(coarse.patches.size());
    std::map<label, std::string> statementOfSurface;
    for (const ng::periodicIdentification& identification : identifications)
    {
        const std::string statement =
            "'identify periodic " + identification.firstSolid + " "
          + identification.secondSolid + "'";
        try
        {
            // The cases that cannot be a pair of cyclic patches, named
            // before Netgen's point pairs are looked at
            for
            (
                const auto& [surface, solid] :
                {
                    std::make_pair(identification.firstSurface, identification.firstSolid),
                    std::make_pair(identification.secondSurface, identification.secondSolid)
                }
            )
            {
                const auto earlier = statementOfSurface.find(surface);
                if (earlier != statementOfSurface.end())
                {
                    throw periodicProblem
                    {
                        "the surface of " + solid + " is in " + earlier->second
                      + " too. A cyclic patch has one neighbour: a surface"
                        " can be in one periodic pair only"
                    };
                }
                statementOfSurface[surface] = statement;
                if (nBoundaryFaces[surface] == 0)
                {
                    throw periodicProblem
                    {
                        nZoneFaces[surface] > 0
                      ? "the surface of " + solid + " lies between two"
                        " regions (top-level solids). Periodic sides must"
                        " bound the meshed solids, not separate them"
                      : "the surface of " + solid + " bounds none of the"
                        " meshed solids"
                    };
                }
            }
            if (identification.points.empty())
            {
                throw periodicProblem
                {
                    "Netgen found no point of " + identification.firstSolid
                  + " whose image is on " + identification.secondSolid
                  + ": they are not a translation of each other. Only"
                    " translational periodic pairs are supported, not"
                    " rotational ones (e.g. the two sides of a wedge)"
                };
            }

            std::map<label, label> image;
            for (const auto& pair : identification.points)
            {
                image[pair[0]] = pair[1];
            }
            const vector3 separation = translationOf
            (
                coarse, image, identification.firstSolid, identification.secondSolid
            );
            periodicPatchPair pp = patchPairOf(coarse, faceOf, image);
            for (const label patch : {pp.first, pp.second})
            {
                if (!pairedBy[patch].empty())
                {
                    throw periodicProblem
                    {
                        "patch " + coarse.patches[patch].name + " is in "
                      + pairedBy[patch] + " too. A cyclic patch has one"
                        " neighbour: a surface can be in one periodic pair"
                        " only (not supported: one side paired with two)"
                    };
                }
                pairedBy[patch] = statement;
            }
            pp.separation = separation;
            const label pairIndex = label(coarse.periodicPatches.size());
            coarse.periodicPatches.push_back(pp);
            for (const auto& [point, imagePoint] : image)
            {
                coarse.periodicPoints.push_back({pairIndex, point, imagePoint});
            }
        }
        catch (const periodicProblem& problem)
        {
            throw FatalError
            (
                msg()
                    << "CSG geometry \"" << fileName_ << "\": cannot make"
                    << " cyclic patches of " << statement << ": "
                    << problem.why,
                "pmsh::csgGeometry::setPeriodicPatches"
            );
        }
    }
}


pmsh::point3 pmsh::csgGeometry::projectToSurface(const point3& p, label s) const
{
    return model_->projectToSurface(p, s);
}


pmsh::point3 pmsh::csgGeometry::projectToEdge
(
    const point3& p,
    label s1,
    label s2
) const
{
    return model_->projectToEdge(p, s1, s2);
}


// ************************************************************************* //
