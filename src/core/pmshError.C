#include "pmshError.H"
#include "foamShims.H"

#include "error.H"
#include "OStringStream.H"

#include <cctype>

pmsh::FatalError::FatalError(const std::string& message, const std::string& where)
:
    std::runtime_error(message),
    message_(message),
    where_(where)
{}


std::string pmsh::str(const point3& p, int precision)
{
    std::ostringstream os;
    os.precision(precision);
    os  << '(' << p[0] << ' ' << p[1] << ' ' << p[2] << ')';
    return os.str();
}


pmsh::FatalError pmsh::FatalError::of(const Foam::error& e)
{
    // Foam::error::what() says only "std::exception": the message, and the
    // file and line of an IOerror
    std::string text = e.message();
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
    {
        text.pop_back();
    }
    // OpenFOAM's operator<< is chosen by the static type: an IOerror's adds
    // the file and line
    Foam::OStringStream os;
    if (const auto* io = dynamic_cast<const Foam::IOerror*>(&e))
    {
        if (!io->ioFileName().empty())
        {
            text += "\n(" + io->ioFileName();
            if (io->ioStartLineNumber() > 0)
            {
                text += " at line " + std::to_string(io->ioStartLineNumber());
            }
            text += ")";
        }
        os  << *io;
    }
    else
    {
        os  << e;
    }
    FatalError converted(text);
    converted.report_ = "\n\n" + os.str() + "\nFOAM exiting\n";
    return converted;
}


pmsh::FatalError pmsh::FatalError::of(const std::exception_ptr& failure)
{
    try
    {
        std::rethrow_exception(failure);
    }
    catch (const FatalError& e)
    {
        return e;
    }
    catch (const Foam::error& e)
    {
        return of(e);
    }
    catch (const std::exception& e)
    {
        return FatalError(e.what());
    }
}


pmsh::foamErrorsThrow::foamErrorsThrow()
:
    error_(foam::throwExceptions(Foam::FatalError, true)),
    ioError_(foam::throwExceptions(Foam::FatalIOError, true))
{}


pmsh::foamErrorsThrow::~foamErrorsThrow()
{
    foam::throwExceptions(Foam::FatalIOError, ioError_);
    foam::throwExceptions(Foam::FatalError, error_);
}


std::string pmsh::FatalError::report() const
{
    if (!report_.empty())
    {
        return report_;
    }
    std::ostringstream os;
    os  << "\n\n--> FOAM FATAL ERROR: \n";

    // Indent every line of the message as OpenFOAM does
    std::istringstream is(message_);
    for (std::string line; std::getline(is, line); )
    {
        os  << "    " << line << '\n';
    }
    if (!where_.empty())
    {
        os  << "\n    From " << where_ << '\n';
    }
    os  << "\nFOAM exiting\n";
    return os.str();
}
