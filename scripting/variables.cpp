#include "variables.hpp"

#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace plab {

namespace {

double ceil_of(double x) { return std::ceil(x); }
double floor_of(double x) { return std::floor(x); }

// A muParser with the scene's values; std::map keeps their addresses fixed.
class Evaluator {
public:
    Evaluator() {
        parser_.DefineFun("ceil", ceil_of);
        parser_.DefineFun("floor", floor_of);
        parser_.DefineConst("pi", M_PI);
    }
    void set(const std::string& name, double value) {
        auto [it, added] = values_.insert_or_assign(name, value);
        if (added) parser_.DefineVar(name, &it->second);
    }
    // The value, or the parser's reason in `why`.
    bool evaluate(const std::string& expression, double& out, std::string& why) {
        try {
            parser_.SetExpr(expression);
            out = parser_.Eval();
        } catch (const mu::Parser::exception_type& e) {
            why = e.GetMsg();
            return false;
        }
        if (!std::isfinite(out)) {
            why = "the value is not finite";
            return false;
        }
        return true;
    }

private:
    mu::Parser parser_;
    std::map<std::string, double> values_;
};

bool is_expression(const json& v) {
    if (!v.is_string()) return false;
    const std::string& s = v.get_ref<const std::string&>();
    return s.size() >= 3 && s.compare(0, 2, "$(") == 0 && s.back() == ')';
}

[[noreturn]] void fail_at(const std::string& path, const std::string& expression, const std::string& why) {
    throw InputError(path, "cannot evaluate \"" + expression + "\": " + why);
}

// Variables may use each other in any order: evaluate what can be, repeat
// until none is left; what is left then names an unknown name or a cycle.
void evaluate_variables(json& vars, Evaluator& eval) {
    const Node n(vars, "scene.variables");
    n.expect_object();
    std::map<std::string, std::string> pending;
    for (auto& [name, v] : vars.items()) {
        if (v.is_number()) eval.set(name, v.get<double>());
        else if (v.is_string()) pending[name] = is_expression(v) ? v.get<std::string>().substr(2, v.get<std::string>().size() - 3) : v.get<std::string>();
        else n.at(name).fail("expected a number or an expression string, got " + show(v));
    }
    while (!pending.empty()) {
        std::string first_name, first_why;
        const std::size_t before = pending.size();
        for (auto it = pending.begin(); it != pending.end();) {
            double value = 0;
            std::string why;
            if (eval.evaluate(it->second, value, why)) {
                eval.set(it->first, value);
                vars[it->first] = value;
                it = pending.erase(it);
            } else {
                if (first_name.empty()) { first_name = it->first; first_why = why; }
                ++it;
            }
        }
        if (pending.size() == before)  // no progress: an unknown name or a cycle
            fail_at("scene.variables." + first_name, pending[first_name],
                    first_why + " (a variable may use the others, but not itself through them)");
    }
}

void substitute(json& v, const std::string& path, Evaluator& eval) {
    if (is_expression(v)) {
        const std::string s = v.get<std::string>(), expr = s.substr(2, s.size() - 3);
        double value = 0;
        std::string why;
        if (!eval.evaluate(expr, value, why)) fail_at(path, s, why);
        v = value;
    } else if (v.is_object()) {
        for (auto& [key, child] : v.items()) substitute(child, path + "." + key, eval);
    } else if (v.is_array()) {
        for (std::size_t i = 0; i < v.size(); ++i) substitute(v[i], path + "[" + std::to_string(i) + "]", eval);
    }
}

} // namespace

json resolve_variables(const json& scene) {
    if (!scene.is_object()) return scene;
    json out = scene;
    Evaluator eval;
    if (out.contains("variables")) evaluate_variables(out["variables"], eval);
    for (auto& [key, child] : out.items())
        if (key != "variables") substitute(child, "scene." + key, eval);
    return out;
}

double evaluate_expression(const std::string& expression, const std::vector<std::pair<std::string, double>>& values,
                           const std::string& path) {
    Evaluator eval;
    for (const auto& [name, v] : values) eval.set(name, v);
    double out = 0;
    std::string why;
    if (!eval.evaluate(expression, out, why)) fail_at(path, expression, why);
    return out;
}

struct Expression::Parser {
    mu::Parser parser;
    std::vector<double> slots;
    std::map<std::string, double> fixed;
};

Expression::Expression(const std::string& text, const std::vector<std::string>& names,
                       const std::vector<std::pair<std::string, double>>& fixed, const std::string& path)
    : parser_(std::make_unique<Parser>()) {
    mu::Parser& p = parser_->parser;
    p.DefineFun("ceil", ceil_of);
    p.DefineFun("floor", floor_of);
    p.DefineConst("pi", M_PI);
    parser_->slots.assign(names.size(), 0.0);  // sized once: the parser holds their addresses
    try {
        for (const auto& [name, v] : fixed) {
            auto [it, added] = parser_->fixed.insert_or_assign(name, v);
            if (added) p.DefineVar(name, &it->second);
        }
        for (std::size_t k = 0; k < names.size(); ++k) p.DefineVar(names[k], &parser_->slots[k]);
        p.SetExpr(text);
        p.Eval();  // parses now: an unknown name is an error here, not in the run
    } catch (const mu::Parser::exception_type& e) {
        fail_at(path, text, e.GetMsg());
    }
}

Expression::~Expression() = default;

double Expression::operator()(const std::vector<double>& values) const {
    std::copy(values.begin(), values.begin() + std::ptrdiff_t(std::min(values.size(), parser_->slots.size())),
              parser_->slots.begin());
    return parser_->parser.Eval();
}

std::vector<std::pair<std::string, double>> scene_variables(const json& scene) {
    std::vector<std::pair<std::string, double>> out;
    if (scene.is_object() && scene.contains("variables") && scene["variables"].is_object())
        for (const auto& [name, v] : scene["variables"].items())
            if (v.is_number()) out.emplace_back(name, v.get<double>());
    return out;
}

} // namespace plab
