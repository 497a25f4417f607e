#include "variables.hpp"

#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <stdexcept>

namespace plab {

namespace {

double ceil_of(double x) { return std::ceil(x); }
double floor_of(double x) { return std::floor(x); }
// K(k), the complete elliptic integral of the first kind (modulus k, |k| < 1):
// analytic periods (a pendulum's, a torque-free top's flip)
double elliptic_k(double k) { return std::fabs(k) < 1 ? std::comp_ellint_1(k) : std::nan(""); }

// What the scene's expressions have beyond muParser's own.
void define_extras(mu::Parser& p) {
    p.DefineFun("ceil", ceil_of);
    p.DefineFun("floor", floor_of);
    p.DefineFun("elliptic_k", elliptic_k);
    p.DefineConst("pi", M_PI);
}

// A muParser with the scene's values; std::map keeps their addresses fixed.
class Evaluator {
public:
    Evaluator() { define_extras(parser_); }
    // false with muParser's reason in `why` for a name it cannot take (a
    // function's or a constant's name)
    bool set(const std::string& name, double value, std::string& why) {
        auto [it, added] = values_.insert_or_assign(name, value);
        if (!added) return true;
        try {
            parser_.DefineVar(name, &it->second);
        } catch (const mu::Parser::exception_type& e) {
            values_.erase(it);
            why = e.GetMsg();
            return false;
        }
        return true;
    }
    void set(const std::string& name, double value) {
        std::string why;
        if (!set(name, value, why)) throw std::logic_error("variable \"" + name + "\": " + why);
    }
    // A variable that is a name (a choice, a group) or true/false: it stands
    // only alone, "$(name)", and is replaced by its JSON value.
    void set_word(const std::string& name, const json& value) { words_[name] = value; }
    const json* word(const std::string& expression) const {
        std::string e = expression;
        e.erase(0, e.find_first_not_of(" \t"));
        e.erase(e.find_last_not_of(" \t") + 1);
        const auto it = words_.find(e);
        return it == words_.end() ? nullptr : &it->second;
    }
    bool is_word(const std::string& name) const { return words_.count(name) > 0; }
    static bool is_reserved(const std::string& name) { return name == "pi" || name == "ceil" || name == "floor"; }
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
    std::map<std::string, json> words_;
};

// A single identifier ("extrapolated_gravity", "dp"), not an expression.
bool is_identifier(const std::string& s) {
    if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
    return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

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
    const auto define = [&](const std::string& name, double value) {
        std::string why;
        if (!eval.set(name, value, why)) n.at(name).fail("cannot be a variable's name: " + why);
    };
    for (auto& [name, v] : vars.items()) {
        if (!is_identifier(name) || eval.is_reserved(name))
            n.at(name).fail("a variable's name is a letter or '_' and then letters, digits or '_', and not pi, ceil or floor");
        if (v.is_number()) define(name, v.get<double>());
        else if (v.is_boolean()) eval.set_word(name, v);
        // a single word that names no other variable (nor pi) is a name, e.g.
        // a choice: "pressure_mode": "extrapolated_gravity"
        else if (v.is_string() && !is_expression(v) && is_identifier(v.get<std::string>()) &&
                 !vars.contains(v.get<std::string>()) && v.get<std::string>() != "pi")
            eval.set_word(name, v);
        else if (v.is_string()) pending[name] = is_expression(v) ? v.get<std::string>().substr(2, v.get<std::string>().size() - 3) : v.get<std::string>();
        else n.at(name).fail("expected a number, true or false, a name or an expression string, got " + show(v));
    }
    while (!pending.empty()) {
        std::string first_name, first_why;
        const std::size_t before = pending.size();
        for (auto it = pending.begin(); it != pending.end();) {
            double value = 0;
            std::string why;
            if (eval.evaluate(it->second, value, why)) {
                define(it->first, value);
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
        if (const json* word = eval.word(expr)) {
            v = *word;
            return;
        }
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
    define_extras(p);
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
