// Scene variables, as LAMMPS's `variable equal` and DualSPHysics's
// <parameters>: a scene names its free quantities once,
//   "variables": {"dp": 0.005, "h": "1.3 * dp", "c0": "10 * sqrt(2 * 9.81 * 0.2)"}
// and any string "$(expression)" elsewhere in the scene is replaced by the
// expression's value. A resolution study is then one scene and
// `--set variables.dp=0.0025`. Expressions are muParser's (+ - * / ^, sqrt,
// exp, ln, log10, sin..., min, max, abs, rint, ?:) plus ceil, floor, pi and
// elliptic_k(k), the complete elliptic integral of the first kind.
// A variable may also be true/false or a name (a single word that names no
// other variable, e.g. "pressure_mode": "extrapolated_gravity", for a choice
// or a group property); such a one stands alone, "$(pressure_mode)".
#pragma once

#include "json_reader.hpp"

#include <memory>
#include <utility>
#include <vector>

namespace plab {

// The scene with every variable evaluated to a number and every "$(...)"
// string replaced by its value. A scene without variables and expressions
// comes back unchanged. Errors name the JSON path, the expression and why.
json resolve_variables(const json& scene);

// Evaluates one expression with the given named values (e.g. a case's
// figures), naming `path` in errors.
double evaluate_expression(const std::string& expression, const std::vector<std::pair<std::string, double>>& values,
                           const std::string& path);

// An expression over named values that change (the columns of a history
// row), parsed once and evaluated many times. Scene variables are fixed
// values in it. Unknown names and syntax errors fail at construction,
// naming `path`.
class Expression {
public:
    Expression(const std::string& text, const std::vector<std::string>& names,
               const std::vector<std::pair<std::string, double>>& fixed, const std::string& path);
    ~Expression();
    Expression(const Expression&) = delete;
    Expression& operator=(const Expression&) = delete;
    // `values` in the order of `names`
    double operator()(const std::vector<double>& values) const;

private:
    struct Parser;
    std::unique_ptr<Parser> parser_;
};

// The numeric variables of a resolved scene, for expressions evaluated later.
std::vector<std::pair<std::string, double>> scene_variables(const json& scene);

} // namespace plab
