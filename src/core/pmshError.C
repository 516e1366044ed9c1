#include "pmshError.H"

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


pmsh::FatalError pmsh::FatalError::preformatted
(
    const std::string& message,
    const std::string& report
)
{
    FatalError e(message);
    e.report_ = report;
    return e;
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
