#include "processSettings.H"
#include "mesherChild.H"
#include "foamShims.H"

#include "argList.H"
#include "Pstream.H"

#include <malloc.h>
#include <cstdlib>

void pmsh::prepareProcess()
{
    meshInFreshProcesses();

    // Large arrays (a rank's tets, faces, addressing) are freed as soon as
    // the next stage has what it needs: keep them in their own mappings,
    // so that freeing them gives the memory back at once (glibc would
    // otherwise raise its mmap threshold after the first such free and
    // keep later arrays in the heap, where freed pages stay resident)
    mallopt(M_MMAP_THRESHOLD, 256*1024);

    // Volume meshing runs in forked children that make no MPI calls (see
    // childProcess.H): Open MPI need not warn about the fork
    ::setenv("OMPI_MCA_mpi_warn_on_fork", "0", 0);
}


void pmsh::addOptions()
{
    Foam::argList::addNote
    (
        "Generate a tetrahedral mesh in parallel (PMSH method) from a Netgen"
        " CSG (.geo) or STL geometry, straight into processor*/"
    );
    foam::noFunctionObjects();
    // processor*/ are what pmshFoam writes: they need not exist yet
    foam::noCheckProcessorDirectories();
    #include "addDictOption.H"
    Foam::argList::addBoolOption
    (
        "overwrite",
        "Replace an existing mesh (only once meshing succeeded on every rank)"
    );
    Foam::argList::addBoolOption
    (
        "noMemoryCheck",
        "Go on even when the memory estimate after the coarse mesh says the"
        " fine mesh cannot fit in this machine's memory"
    );
    Foam::argList::addOption
    (
        "decomposeParDict",
        "file",
        "Use specified file for the decomposition dictionary"
    );
}


void pmsh::startRun(const Foam::argList& args)
{
    if (!foam::checkRootCase(args))
    {
        Foam::FatalError.exit();
    }

    // Netgen and HXT divide by zero and take square roots of negatives on
    // purpose (and test the result): OpenFOAM's trapFpe would kill them
    foam::unsetFpeTrapping();

    // Netgen's Mesh asks MPI for its rank, also in a serial run
    if (!Foam::Pstream::parRun())
    {
        foam::initNullMPI();
    }
}


// ************************************************************************* //
