#include "patchTypes.H"
#include "meshPatch.H"

void pmsh::setPatchTypes(CoarseMesh& coarse, const meshSettings& settings)
{
    for (meshPatch& p : coarse.patches)
    {
        const meshSettings::patchTypeChoice choice = settings.choosePatchType(p.name);
        p.type = choice.type;
        p.typeOrigin = choice.origin;
        p.groups = settings.patchGroups(p.name);
    }
    // The geometry's periodic pairs are cyclic, whatever pmshDict says
    for (const periodicPatchPair& pp : coarse.periodicPatches)
    {
        meshPatch& first = coarse.patches[pp.first];
        meshPatch& second = coarse.patches[pp.second];
        first.type = second.type = "cyclic";
        first.typeOrigin = second.typeOrigin = "identify periodic in the geometry";
        first.neighbourPatch = second.name;
        second.neighbourPatch = first.name;
        first.separation = pp.separation;
        second.separation = -1.0*pp.separation;
    }
}


// ************************************************************************* //
