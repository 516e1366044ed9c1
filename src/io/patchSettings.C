/*---------------------------------------------------------------------------*\
  pmshFoam: what pmshDict's patches sub-dictionary says of one patch: its
  type, its coarse size and its prism layers, each from the entry matching
  the patch's name (the literal name first, else the last matching
  regular expression). meshSettings.C checked every entry when it read the
  dictionary.
\*---------------------------------------------------------------------------*/
#include "meshSettings.H"
#include "foamShims.H"
#include "dictEntries.H"

#include <algorithm>
#include <cctype>

namespace pmsh
{

meshSettings::patchTypeChoice meshSettings::choosePatchType
(
    const std::string& patchName
) const
{
    // REGEX search: the literal name first, then the patterns, last first
    const Foam::entry* e = foam::findEntry(patches, patchName, true);
    if (e && e->isDict() && foam::found(e->dict(), "type"))
    {
        return
        {
            foam::get<Foam::word>(e->dict(), "type"),
            "patches entry \"" + std::string(e->keyword()) + "\""
        };
    }

    // A CFD user names open boundaries and symmetry planes so; a wall they
    // must name in pmshDict only if it is called e.g. "inletPipeWall"
    std::string lower(patchName);
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    const auto has = [&](const char* word) { return lower.find(word) != std::string::npos; };
    if (has("wall"))
    {
        return {"wall", "its name"};
    }
    for
    (
        const char* open
      : {"inlet", "outlet", "inflow", "outflow", "farfield", "far_field",
         "freestream", "atmosphere", "ambient", "opening"}
    )
    {
        if (has(open))
        {
            return {"patch", "its name (\"" + std::string(open) + "\": flow goes through)"};
        }
    }
    if (has("symm"))
    {
        return {"symmetry", "its name"};
    }
    return {"wall", "default"};
}


double meshSettings::patchMaxCellSize(const std::string& patchName) const
{
    // The same entry as patchType's
    const Foam::entry* e = foam::findEntry(patches, patchName, true);
    return
        e && e->isDict()
      ? foam::getOrDefault<Foam::scalar>(e->dict(), "maxCellSize", 0)
      : 0;
}


bool meshSettings::hasPatchSizes() const
{
    for (const Foam::entry& e : patches)
    {
        if (e.isDict() && foam::found(e.dict(), "maxCellSize"))
        {
            return true;
        }
    }
    return false;
}


std::vector<std::string> meshSettings::patchGroups(const std::string& patchName) const
{
    // The same entry as patchType's
    const Foam::entry* e = foam::findEntry(patches, patchName, true);
    std::vector<std::string> groups;
    if (e && e->isDict())
    {
        if (const Foam::entry* g = foam::findEntry(e->dict(), "inGroups"))
        {
            stringList(*g, groups, false);      // checked by readMeshSettings
        }
    }
    return groups;
}


layerSpecification meshSettings::patchLayers(const std::string& patchName) const
{
    // The same entry as patchType's
    const Foam::entry* e = foam::findEntry(patches, patchName, true);
    return
        e && e->isDict()
      ? readLayerSpecification(e->dict(), patchName)
      : layerSpecification();
}


} // End namespace pmsh


// ************************************************************************* //
