#include "layerSpecification.H"
#include "dictEntries.H"
#include "foamShims.H"

#include "error.H"

#include <cmath>
#include <functional>
#include <limits>

namespace pmsh
{

namespace
{

const char* const where = "pmsh::readLayerSpecification";

// The valid ranges, in one place for the checks and their messages
constexpr int maxLayers = 100;
constexpr double maxExpansionRatio = 5;

const char* const thicknessEntries[] =
    {"firstLayerThickness", "finalLayerThickness", "totalThickness"};


// Every entry is read and checked the one way (dictEntries.H)
const entryChecks check(where);


//- Entry `key` of patch patchName, checked against [lo, hi] (aboveZero:
//  > 0); deflt where the patch has none
double boundedEntry
(
    const Foam::dictionary& d,
    const std::string& patchName,
    const char* key,
    double deflt,
    double lo,
    double hi
)
{
    return check.bounded
    (
        d, key, deflt, lo, hi, false, validRange(lo, hi),
        " of patch '" + patchName + "'"
    );
}


//- The root in [lo, hi] of an increasing (or decreasing) function by
//  bisection; f(lo) and f(hi) have opposite signs.
double bisect(const std::function<double(double)>& f, double lo, double hi)
{
    const bool increasing = f(hi) > f(lo);
    for (int i = 0; i < 200 && hi - lo > 1e-15*hi; ++i)
    {
        const double mid = 0.5*(lo + hi);
        ((f(mid) > 0) == increasing ? hi : lo) = mid;
    }
    return 0.5*(lo + hi);
}


//- Sum of r^i, i = 0..n-1, in a fixed order.
double geometricSum(double r, int n)
{
    double s = 0, term = 1;
    for (int i = 0; i < n; ++i)
    {
        s += term;
        term *= r;
    }
    return s;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * layerSpecification  * * * * * * * * * * * //

double layerSpecification::layerThickness(int k) const
{
    return firstLayerThickness*std::pow(expansionRatio, k - 1);
}


double layerSpecification::levelOffset(int k) const
{
    // Summed from the wall up, always in this order: every rank gets the
    // same bits for the same level
    double offset = 0;
    for (int i = 1; i <= k; ++i)
    {
        offset += layerThickness(i);
    }
    return offset;
}


bool layerSpecification::operator==(const layerSpecification& o) const
{
    return
        nLayers == o.nLayers
     && firstLayerThickness == o.firstLayerThickness
     && expansionRatio == o.expansionRatio
     && minThickness == o.minThickness
     && featureAngle == o.featureAngle
     && maxThicknessToGapRatio == o.maxThicknessToGapRatio;
}


const std::vector<std::string>& layerSpecificationEntries()
{
    static const std::vector<std::string> entries
    {
        "layers", "firstLayerThickness", "finalLayerThickness",
        "totalThickness", "expansionRatio", "minThickness", "featureAngle",
        "maxThicknessToGapRatio"
    };
    return entries;
}


layerSpecification readLayerSpecification
(
    const Foam::dictionary& d,
    const std::string& patchName
)
{
    layerSpecification spec;

    if (!foam::found(d, "layers"))
    {
        // The other entries mean nothing without it: say so, not ignore them
        for (const std::string& key : layerSpecificationEntries())
        {
            if (foam::found(d, key))
            {
                check.error(d, key.c_str())
                    << "Entry '" << key.c_str() << "' of patch '"
                    << patchName.c_str() << "' needs 'layers' (the number of"
                    << " prism layers, 1.." << maxLayers << ") in the same"
                    << " patch" << Foam::exit(Foam::FatalIOError);
            }
        }
        return spec;
    }

    spec.nLayers = int
    (
        check.bounded
        (
            d, "layers", 0, 0, maxLayers, true,
            "Valid values are 0 (no layers) .. " + std::to_string(maxLayers),
            " of patch '" + patchName + "'"
        )
    );
    if (!spec.layered())
    {
        return spec;
    }

    // The stack's thickness: one of the three with expansionRatio, or two
    // without it
    std::vector<const char*> given;
    for (const char* key : thicknessEntries)
    {
        if (foam::found(d, key)) given.push_back(key);
    }
    const bool ratioGiven = foam::found(d, "expansionRatio");
    const std::string choices =
        "Give one of firstLayerThickness, finalLayerThickness and"
        " totalThickness (with expansionRatio, default 1.2), or two of them"
        " (without expansionRatio)";
    if (given.empty() || given.size() == 3 || (given.size() == 2 && ratioGiven))
    {
        check.error(d, given.empty() ? "layers" : ratioGiven ? "expansionRatio" : given[2])
            << "Patch '" << patchName.c_str() << "' has layers "
            << spec.nLayers << " and "
            << (given.empty() ? "no thickness" : "too many thickness entries")
            << '\n' << choices.c_str() << Foam::exit(Foam::FatalIOError);
    }

    auto thickness = [&](const char* key)
    {
        return boundedEntry
        (
            d, patchName, key, 0, aboveZero, std::numeric_limits<double>::max()
        );
    };
    const double first = thickness("firstLayerThickness");
    const double finalLayer = thickness("finalLayerThickness");
    const double total = thickness("totalThickness");
    const int L = spec.nLayers;

    if (given.size() == 1)
    {
        const double r = boundedEntry
        (
            d, patchName, "expansionRatio", spec.expansionRatio, 1, maxExpansionRatio
        );
        spec.expansionRatio = r;
        spec.firstLayerThickness =
            first > 0 ? first
          : finalLayer > 0 ? finalLayer/std::pow(r, L - 1)
          : total/geometricSum(r, L);
    }
    else
    {
        // The ratio that makes the two agree, within 1..maxExpansionRatio
        std::function<double(double)> mismatch;
        if (first > 0 && finalLayer > 0)
        {
            mismatch = [&](double r) { return first*std::pow(r, L - 1) - finalLayer; };
        }
        else if (first > 0)
        {
            mismatch = [&](double r) { return first*geometricSum(r, L) - total; };
        }
        else
        {
            mismatch = [&](double r) { return finalLayer*geometricSum(1/r, L) - total; };
        }
        const double lo = 1, hi = maxExpansionRatio;
        const double fLo = mismatch(lo), fHi = mismatch(hi);
        const double tolerance = 1e-12*std::max(std::abs(fLo), std::abs(fHi));
        double r = 0;
        if (std::abs(fLo) <= tolerance) r = lo;
        else if (std::abs(fHi) <= tolerance) r = hi;
        else if ((fLo < 0) != (fHi < 0) && L > 1) r = bisect(mismatch, lo, hi);
        if (r == 0)
        {
            check.error(d, given[1])
                << "Entries '" << given[0] << "' and '" << given[1]
                << "' of patch '" << patchName.c_str() << "' do not fit "
                << L << " layers with an expansionRatio between 1 and "
                << maxExpansionRatio << '\n' << choices.c_str()
                << Foam::exit(Foam::FatalIOError);
        }
        spec.expansionRatio = r;
        spec.firstLayerThickness = first > 0 ? first : finalLayer/std::pow(r, L - 1);
    }

    spec.minThickness = boundedEntry
    (
        d, patchName, "minThickness", spec.firstLayerThickness, 0, spec.totalThickness()
    );
    spec.featureAngle =
        boundedEntry(d, patchName, "featureAngle", spec.featureAngle, 0, 180);
    spec.maxThicknessToGapRatio = boundedEntry
    (
        d, patchName, "maxThicknessToGapRatio", spec.maxThicknessToGapRatio, aboveZero, 0.5
    );
    return spec;
}

} // End namespace pmsh
