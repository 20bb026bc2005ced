// Formulas on the command line (formula.h).
#include "formula.h"

#include <cmath>
#include <numbers>

#include <muParser.h>

#include "limsurf/core/error.h"

namespace limsurf::cli {

/// Values of the formula @p expression (variables x, y, z; constant pi) at the rows of @p X.
/// @throws InputError naming the formula and muParser's message
Eigen::VectorXd evaluate_formula(const std::string& what, const std::string& expression, const Points& X) {
    Eigen::VectorXd out(X.rows());
    try {
        mu::Parser parser;
        double x = 0.0, y = 0.0, z = 0.0;
        parser.DefineVar("x", &x);
        parser.DefineVar("y", &y);
        parser.DefineVar("z", &z);
        parser.DefineConst("pi", std::numbers::pi);
        parser.SetExpr(expression);
        // muParser reads "a, b" as several expressions and Eval() returns the last: a user who
        // wrote a vector, or a decimal comma, would get a silently different function.
        (void)parser.Eval();  // parses; the value at the origin is not used
        LIMSURF_CHECK(parser.GetNumResults() == 1, InputError, what, " '", expression, "' has ", parser.GetNumResults(),
                      " comma-separated values: give one expression (decimal point: '.')");
        for (Eigen::Index v = 0; v < X.rows(); ++v) {
            x = X(v, 0);
            y = X(v, 1);
            z = X(v, 2);
            out(v) = parser.Eval();
            LIMSURF_CHECK(std::isfinite(out(v)), InputError, what, " '", expression, "' is not finite at (x, y, z) = (",
                          x, ", ", y, ", ", z, ")");
        }
    } catch (const mu::Parser::exception_type& e) {
        throw InputError(detail::concat(what, " '", expression, "': ", e.GetMsg()));
    }
    return out;
}

void check_formula(const std::string& what, const std::string& expression) {
    (void)evaluate_formula(what, expression, Points::Zero(0, 3));
}

}  // namespace limsurf::cli
