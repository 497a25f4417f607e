// PNG pictures with cairo (a Debian-packaged 2D drawing library): the scene
// is drawn in world coordinates through one affine map, so balls keep their
// true size; text and legend are drawn in pixels on top.
#include "pictures.hpp"

#include <plab_host/errors.hpp>

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <unordered_map>

namespace plab {

namespace {

struct Rgb {
    double r, g, b;
};

// Viridis (perceptually uniform, readable in grey), 9 control points.
Rgb colour_map(double t) {
    static const Rgb stops[] = {{0.267, 0.005, 0.329}, {0.278, 0.175, 0.483}, {0.231, 0.322, 0.546},
                                {0.173, 0.449, 0.558}, {0.128, 0.567, 0.551}, {0.153, 0.680, 0.504},
                                {0.361, 0.785, 0.388}, {0.668, 0.862, 0.196}, {0.993, 0.906, 0.144}};
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 8.0;
    const int i = std::min(int(t), 7);
    const double f = t - i;
    const Rgb& a = stops[i];
    const Rgb& b = stops[i + 1];
    return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

// Distinct colours for groups and curves (Okabe–Ito, colour-blind safe).
Rgb category(int k) {
    static const Rgb c[] = {{0.000, 0.447, 0.698}, {0.835, 0.369, 0.000}, {0.000, 0.620, 0.451},
                            {0.800, 0.475, 0.655}, {0.941, 0.894, 0.259}, {0.337, 0.706, 0.914},
                            {0.902, 0.624, 0.000}, {0.3, 0.3, 0.3}};
    return c[((k % 8) + 8) % 8];
}

std::string number(double v, const char* fmt = "%.4g") {
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

// A "nice" step (1, 2 or 5 x 10^k) close to span/target.
double nice_step(double span, int target) {
    if (!(span > 0)) return 1.0;
    const double raw = span / target, mag = std::pow(10.0, std::floor(std::log10(raw)));
    const double f = raw / mag;
    return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * mag;
}

std::string length_text(double m) {
    if (m >= 1) return number(m, "%g") + " m";
    if (m >= 0.01) return number(m * 100, "%g") + " cm";
    if (m >= 0.001) return number(m * 1000, "%g") + " mm";
    return number(m * 1e6, "%g") + " um";
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size = 14, double align = 0.0) {
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    cairo_move_to(cr, x - align * e.x_advance, y);
    cairo_show_text(cr, s.c_str());
}

void save(cairo_surface_t* surface, const std::string& path) {
    const std::filesystem::path p(path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    const std::string tmp = path + ".tmp";
    const cairo_status_t st = cairo_surface_write_to_png(surface, tmp.c_str());
    if (st != CAIRO_STATUS_SUCCESS) throw std::runtime_error("cannot write " + path + ": " + cairo_status_to_string(st));
    std::filesystem::rename(tmp, path);
}

} // namespace

// Bounding box of the balls and finite wall facets (x–y).
std::vector<double> snapshot_view(const World& w) {
    double x0, y0, x1, y1;
    x0 = y0 = kInf;
    x1 = y1 = -kInf;
    auto grow = [&](double x, double y, double r) {
        x0 = std::min(x0, x - r); x1 = std::max(x1, x + r);
        y0 = std::min(y0, y - r); y1 = std::max(y1, y + r);
    };
    for (std::size_t i = 0; i < w.bodies.size(); ++i)
        grow(w.bodies.position[i].x(), w.bodies.position[i].y(), w.bodies.radius[i]);
    for (const Facet& f : w.walls.facets)
        if (f.kind == FacetKind::segment) { grow(f.a.x(), f.a.y(), 0); grow(f.b.x(), f.b.y(), 0); }
    if (!(x1 > x0)) { x0 = -1; x1 = 1; }
    if (!(y1 > y0)) { y0 = -1; y1 = 1; }
    const double pad = 0.03 * std::max(x1 - x0, y1 - y0);
    return {x0 - pad, y0 - pad, x1 + pad, y1 + pad};
}

std::vector<std::string> snapshot_field_names(const World& w) {
    std::vector<std::string> names = {"velocity", "force", "group", "id", "stress_xx", "stress_yy", "stress_xy",
                                      "mean_stress", "broken_bonds"};
    for (std::size_t f = 0; f < w.fields.names().size(); ++f)
        if (field_computed(w, int(f))) names.push_back(w.fields.names()[f]);
    return names;
}

std::vector<double> snapshot_values(const World& w, const std::string& field, std::string& unit) {
    const Bodies& b = w.bodies;
    std::vector<double> v(b.size(), 0.0);
    if (field == "velocity" || field == "force") {
        unit = field == "velocity" ? "m/s" : "N";
        for (std::size_t i = 0; i < b.size(); ++i) v[i] = (field == "velocity" ? b.velocity[i] : b.force[i]).norm();
    } else if (field == "group" || field == "id") {
        unit = "";
        for (std::size_t i = 0; i < b.size(); ++i) v[i] = field == "group" ? b.group[i] : double(b.id[i]);
    } else if (field.rfind("stress_", 0) == 0 || field == "mean_stress") {
        unit = "Pa";  // per-ball average stress, tension positive
        const auto sigma = ball_stress(w);
        for (std::size_t i = 0; i < b.size(); ++i)
            v[i] = field == "stress_xx" ? sigma[i](0, 0) : field == "stress_yy" ? sigma[i](1, 1)
                 : field == "stress_xy" ? sigma[i](0, 1) : 0.5 * (sigma[i](0, 0) + sigma[i](1, 1));
        if (field != "stress_xx" && field != "stress_yy" && field != "stress_xy" && field != "mean_stress")
            throw InputError("field", "unknown stress component '" + field + "'; use stress_xx, stress_yy, stress_xy, mean_stress");
    } else if (field == "broken_bonds") {
        unit = "";  // damage: bonds each ball has lost
        std::unordered_map<BodyId, std::size_t> index;
        for (std::size_t i = 0; i < b.size(); ++i) index[b.id[i]] = i;
        for (const BondBreak& br : w.bond_breaks)
            for (BodyId id : {br.id1, br.id2})
                if (index.count(id)) v[index[id]] += 1;
    } else {
        const int f = w.fields.index(field);
        if (f < 0) {
            std::string known;
            for (const auto& n : snapshot_field_names(w)) known += (known.empty() ? "" : ", ") + n;
            throw InputError("field", "unknown field '" + field + "' to colour balls by; fields: " + known);
        }
        unit = w.fields.unit(f) == "1" ? "" : w.fields.unit(f);  // "1": dimensionless
        v = w.fields.column(f);
    }
    return v;
}

std::size_t SnapshotFrame::bytes() const {
    return sizeof(float) * (x.size() + y.size() + radius.size() + value.size() + walls.size() + bonds.size() + breaks.size()) +
           sizeof(int) * group.size();
}

namespace {

bool listed(const std::vector<int>& groups, int g) { return std::find(groups.begin(), groups.end(), g) != groups.end(); }

// Intact bonds as segments between centres; broken ones while the two balls
// are still near each other (once the pieces fly apart a line would cross
// the picture: the field's colour says enough).
void capture_bonds(const World& w, SnapshotFrame& f) {
    const Bodies& b = w.bodies;
    auto segment = [](std::vector<float>& out, const Vec& p, const Vec& q) {
        out.insert(out.end(), {float(p.x()), float(p.y()), float(q.x()), float(q.y())});
    };
    for (std::size_t m = 0; m < w.model_count(); ++m) {
        const ContactTable s = w.model(m).balls();
        for (std::size_t k = 0; k < s.size(); ++k)
            if (s.bonded(k)) segment(f.bonds, b.position[s.end1(k)], b.position[s.end2(k)]);
    }
    std::unordered_map<BodyId, std::size_t> index;
    for (std::size_t i = 0; i < b.size(); ++i) index[b.id[i]] = i;
    for (const BondBreak& br : w.bond_breaks) {
        if (!index.count(br.id1) || !index.count(br.id2)) continue;
        const std::size_t i = index[br.id1], j = index[br.id2];
        if ((b.position[i] - b.position[j]).norm() <= 1.5 * (b.radius[i] + b.radius[j]))
            segment(f.breaks, b.position[i], b.position[j]);
    }
}

} // namespace

SnapshotFrame capture_snapshot(const World& w, const SnapshotOptions& opt) {
    SnapshotFrame f;
    f.time = w.time;
    f.step = w.step_count;
    f.field = opt.field;
    f.group_names = w.group_names();
    const std::vector<double> value = snapshot_values(w, opt.field, f.unit);
    const Bodies& b = w.bodies;
    for (std::size_t i = 0; i < b.size(); ++i) {
        if (listed(opt.hidden_groups, b.group[i])) continue;
        f.x.push_back(float(b.position[i].x()));
        f.y.push_back(float(b.position[i].y()));
        f.radius.push_back(float(b.radius[i]));
        f.value.push_back(float(value[i]));
        f.group.push_back(b.group[i]);
    }
    for (const Facet& fc : w.walls.facets)
        if (fc.kind == FacetKind::segment) f.walls.insert(f.walls.end(), {float(fc.a.x()), float(fc.a.y()), float(fc.b.x()), float(fc.b.y())});
    if (opt.bonds) capture_bonds(w, f);
    return f;
}

std::pair<double, double> value_range(const SnapshotFrame& f, const SnapshotOptions& opt) {
    double lo = kInf, hi = -kInf;
    for (std::size_t i = 0; i < f.value.size(); ++i)
        if (std::isfinite(f.value[i]) && !listed(opt.greyed_groups, f.group[i])) {
            lo = std::min(lo, double(f.value[i]));
            hi = std::max(hi, double(f.value[i]));
        }
    if (lo > hi) return {std::nan(""), std::nan("")};
    return {lo, hi};
}

namespace {

constexpr int kBarWidth = 120, kFooter = 46, kAxisLeft = 64, kAxisBottom = 40, kAxisPad = 12;

// Ticks at the multiples of a 1-2-5 step inside [lo, hi].
std::vector<double> ticks_within(double lo, double hi, int target) {
    const double step = nice_step(hi - lo, target);
    std::vector<double> t;
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
        t.push_back(std::fabs(v) < 1e-9 * step ? 0.0 : v);
    return t;
}

void draw_scene_axes(cairo_t* cr, const SnapshotLayout& L, const std::vector<double>& view) {
    const double x0 = view[0], y0 = view[1], x1 = view[2], y1 = view[3];
    const double px0 = L.left, px1 = L.left + (x1 - x0) * L.scale, py0 = L.top + (y1 - y0) * L.scale;
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, px0, L.top, px1 - px0, py0 - L.top);
    cairo_stroke(cr);
    const int target = std::max(3, int((px1 - px0) / 110));
    for (double x : ticks_within(x0, x1, target)) {
        const double p = L.left + (x - x0) * L.scale;
        cairo_move_to(cr, p, py0); cairo_line_to(cr, p, py0 + 5); cairo_stroke(cr);
        text(cr, p, py0 + 18, number(x, "%g"), 11, 0.5);
    }
    for (double y : ticks_within(y0, y1, std::max(3, int((py0 - L.top) / 80)))) {
        const double p = L.top + (y1 - y) * L.scale;
        cairo_move_to(cr, px0 - 5, p); cairo_line_to(cr, px0, p); cairo_stroke(cr);
        text(cr, px0 - 8, p + 4, number(y, "%g"), 11, 1.0);
    }
    text(cr, 0.5 * (px0 + px1), py0 + 34, "x [m]", 12, 0.5);
    cairo_save(cr);
    cairo_translate(cr, 14, 0.5 * (L.top + py0));
    cairo_rotate(cr, -M_PI / 2);
    text(cr, 0, 0, "y [m]", 12, 0.5);
    cairo_restore(cr);
}

void draw_colour_bar(cairo_t* cr, const SnapshotFrame& f, const SnapshotLayout& L, double vmin, double vmax) {
    const double bx = L.width - kBarWidth + 20, by = 30, bh = std::max(100.0, std::min(300.0, L.height - kFooter - 60.0));
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, bx - 8, by - 12, f.field + (f.unit.empty() ? "" : " [" + f.unit + "]"), 12);
    if (f.field == "group") {
        for (std::size_t g = 0; g < f.group_names.size(); ++g) {
            const Rgb c = category(int(g));
            cairo_set_source_rgb(cr, c.r, c.g, c.b);
            cairo_rectangle(cr, bx, by + 20.0 * g, 14, 14);
            cairo_fill(cr);
            cairo_set_source_rgb(cr, 0, 0, 0);
            text(cr, bx + 20, by + 20.0 * g + 12, f.group_names[g], 12);
        }
        return;
    }
    for (int k = 0; k < int(bh); ++k) {
        const Rgb c = colour_map(1.0 - k / bh);
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_rectangle(cr, bx, by + k, 18, 1.2);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    for (double v : ticks_within(vmin, vmax, 5)) {
        const double y = by + bh * (1 - (v - vmin) / (vmax - vmin));
        cairo_move_to(cr, bx + 18, y); cairo_line_to(cr, bx + 22, y); cairo_stroke(cr);
        text(cr, bx + 25, y + 4, number(v, "%g"), 11);
    }
}

void draw_footer(cairo_t* cr, const SnapshotFrame& f, const SnapshotLayout& L, const std::vector<double>& view) {
    const double fy = L.height - 16;
    text(cr, 10, fy, "t = " + number(f.time, "%.5g") + " s   step " + std::to_string(f.step) + "   " +
                         std::to_string(f.x.size()) + " balls", 14);
    const double bar_m = nice_step(view[2] - view[0], 5);
    const double sx1 = L.width - kBarWidth - 20, sx0 = sx1 - bar_m * L.scale;
    cairo_set_line_width(cr, 3);
    cairo_move_to(cr, sx0, fy - 4);
    cairo_line_to(cr, sx1, fy - 4);
    cairo_stroke(cr);
    text(cr, 0.5 * (sx0 + sx1), fy - 10, length_text(bar_m), 12, 0.5);
}

void draw_segments(cairo_t* cr, const std::vector<float>& seg, const std::function<double(double)>& px,
                   const std::function<double(double)>& py) {
    for (std::size_t k = 0; k + 3 < seg.size(); k += 4) {
        cairo_move_to(cr, px(seg[k]), py(seg[k + 1]));
        cairo_line_to(cr, px(seg[k + 2]), py(seg[k + 3]));
    }
    cairo_stroke(cr);
}

} // namespace

SnapshotLayout snapshot_layout(const SnapshotOptions& opt, const std::vector<double>& view) {
    const int W = std::max(300, opt.width);
    const double left = opt.axes ? kAxisLeft : 0, top = opt.axes ? kAxisPad : 0;
    const double scene_px = W - kBarWidth - left - (opt.axes ? kAxisPad : 0);
    const double scale = scene_px / (view[2] - view[0]);  // px per metre
    const int H = int(std::ceil(top + (view[3] - view[1]) * scale)) + (opt.axes ? kAxisBottom : 0) + kFooter;
    return {left, top, scale, W, std::max(H, 200)};
}

void draw_snapshot_png(const SnapshotFrame& f, const SnapshotOptions& opt, const std::vector<double>& view,
                       double vmin, double vmax, const std::string& path) {
    if (!(vmax > vmin)) { vmin = std::isfinite(vmin) ? vmin : 0.0; vmax = vmin + 1.0; }
    const SnapshotLayout L = snapshot_layout(opt, view);
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, L.width, L.height);
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    const std::function<double(double)> px = [&](double x) { return L.left + (x - view[0]) * L.scale; };
    const std::function<double(double)> py = [&](double y) { return L.top + (view[3] - y) * L.scale; };
    cairo_rectangle(cr, L.left, L.top, (view[2] - view[0]) * L.scale, (view[3] - view[1]) * L.scale);
    cairo_clip(cr);  // balls that left the view are cut, not drawn over the legend
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, 2.0);
    draw_segments(cr, f.walls, px, py);
    const bool categorical = f.field == "group";
    for (std::size_t i = 0; i < f.x.size(); ++i) {
        const Rgb c = listed(opt.greyed_groups, f.group[i]) ? Rgb{0.82, 0.82, 0.82}
                      : categorical                         ? category(int(f.value[i]))
                                                            : colour_map((f.value[i] - vmin) / (vmax - vmin));
        cairo_arc(cr, px(f.x[i]), py(f.y[i]), std::max(0.5, f.radius[i] * L.scale), 0, 2 * M_PI);
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_fill(cr);
    }
    cairo_set_line_width(cr, std::max(0.6, 0.15 * L.scale * (f.radius.empty() ? 0.0 : f.radius[0])));
    cairo_set_source_rgba(cr, 0.2, 0.2, 0.2, 0.6);
    draw_segments(cr, f.bonds, px, py);
    cairo_set_source_rgb(cr, 0.85, 0.0, 0.0);
    cairo_set_line_width(cr, 2.5);
    draw_segments(cr, f.breaks, px, py);
    for (std::size_t k = 0; k + 3 < f.breaks.size(); k += 4) {  // a cross at each break
        const double cx = px(0.5 * (f.breaks[k] + f.breaks[k + 2])), cy = py(0.5 * (f.breaks[k + 1] + f.breaks[k + 3])), s = 4;
        cairo_move_to(cr, cx - s, cy - s); cairo_line_to(cr, cx + s, cy + s);
        cairo_move_to(cr, cx - s, cy + s); cairo_line_to(cr, cx + s, cy - s);
    }
    cairo_stroke(cr);
    cairo_reset_clip(cr);
    if (opt.axes) draw_scene_axes(cr, L, view);
    draw_colour_bar(cr, f, L, vmin, vmax);
    draw_footer(cr, f, L, view);
    cairo_destroy(cr);
    save(surface, path);
    cairo_surface_destroy(surface);
}

void write_snapshot_png(const World& w, const SnapshotOptions& opt, const std::string& path) {
    const SnapshotFrame f = capture_snapshot(w, opt);
    const auto [lo, hi] = opt.range_min < opt.range_max ? std::pair{opt.range_min, opt.range_max} : value_range(f, opt);
    draw_snapshot_png(f, opt, opt.view.size() == 4 ? opt.view : snapshot_view(w), lo, hi, path);
}

namespace {

// One axis of a plot: the drawn range (rounded out to ticks) and whether it
// is logarithmic. at() maps a value to [0, 1] along the axis.
struct PlotAxis {
    double lo = 0, hi = 1;
    bool log = false;
    double step = 1;  // linear: the tick spacing the range was rounded to
    double at(double v) const {
        return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    }
    bool shows(double v) const { return std::isfinite(v) && (!log || v > 0); }
    std::vector<double> ticks() const {
        std::vector<double> t;
        if (!log) {
            for (double v = lo; v <= hi + 0.5 * step; v += step) t.push_back(std::fabs(v) < 1e-12 * step ? 0.0 : v);
            return t;
        }
        // decades; over fewer than three decades 2 and 5 as well
        const bool fine = std::log10(hi / lo) < 3;
        for (double d = lo; d <= hi * 1.0001; d *= 10)
            for (double m : {1.0, 2.0, 5.0})
                if ((m == 1.0 || fine) && m * d <= hi * 1.0001) t.push_back(m * d);
        return t;
    }
};

// The axis over [lo, hi] (the data's range), rounded out to nice ticks.
PlotAxis make_axis(double lo, double hi, bool log) {
    PlotAxis a{lo, hi, log, 1.0};
    if (log) {
        if (!(lo > 0 && std::isfinite(lo))) { a.lo = 1; a.hi = 10; return a; }
        a.lo = std::pow(10.0, std::floor(std::log10(lo) + 1e-9));
        a.hi = std::pow(10.0, std::ceil(std::log10(hi) - 1e-9));
        if (!(a.hi > a.lo)) a.hi = 10 * a.lo;
        return a;
    }
    if (!(hi > lo)) { a.lo = std::isfinite(lo) ? lo - 1 : 0; a.hi = a.lo + 2; }
    a.step = nice_step(a.hi - a.lo, 6);
    a.lo = std::floor(a.lo / a.step) * a.step;
    a.hi = std::ceil(a.hi / a.step) * a.step;
    return a;
}

// The data range of the curves along x (or y, with their error bands).
std::pair<double, double> data_range(const Plot& plot, bool y, bool log) {
    double lo = kInf, hi = -kInf;
    for (const Curve& c : plot.curves)
        for (std::size_t k = 0; k < c.x.size() && k < c.y.size(); ++k) {
            if (!std::isfinite(c.x[k]) || !std::isfinite(c.y[k])) continue;
            const double v = y ? c.y[k] : c.x[k], band = y ? c.band : 0.0;
            for (double w : {v * (1 - band), v, v * (1 + band)})
                if (!log || w > 0) { lo = std::min(lo, w); hi = std::max(hi, w); }
        }
    return {lo, hi};
}

struct PlotFrame {
    PlotAxis x, y;
    double L, R, T, B;
    int W, H;
    double px(double v) const { return L + x.at(v) * (W - L - R); }
    double py(double v) const { return H - B - y.at(v) * (H - T - B); }
    bool shows(double vx, double vy) const { return x.shows(vx) && y.shows(vy); }
};

void draw_axes(cairo_t* cr, const Plot& plot, const PlotFrame& f) {
    cairo_set_line_width(cr, 1);
    for (double x : f.x.ticks()) {
        cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
        cairo_move_to(cr, f.px(x), f.py(f.y.lo)); cairo_line_to(cr, f.px(x), f.py(f.y.hi)); cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        text(cr, f.px(x), f.H - f.B + 18, number(x), 12, 0.5);
    }
    for (double y : f.y.ticks()) {
        cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
        cairo_move_to(cr, f.px(f.x.lo), f.py(y)); cairo_line_to(cr, f.px(f.x.hi), f.py(y)); cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        text(cr, f.L - 6, f.py(y) + 4, number(y), 12, 1.0);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, f.L, f.T, f.W - f.L - f.R, f.H - f.T - f.B);
    cairo_stroke(cr);
    text(cr, f.W / 2.0, 24, plot.title, 15, 0.5);
    text(cr, (f.L + f.W - f.R) / 2.0, f.H - 12, plot.x_label + (f.x.log ? " (log)" : ""), 13, 0.5);
    cairo_save(cr);
    cairo_translate(cr, 18, (f.T + f.H - f.B) / 2.0);
    cairo_rotate(cr, -M_PI / 2);
    text(cr, 0, 0, plot.y_label + (f.y.log ? " (log)" : ""), 13, 0.5);
    cairo_restore(cr);
}

// Error bands: an error bar on each marker, a shaded band along a line.
void draw_band(cairo_t* cr, const Curve& cv, const Rgb& col, const PlotFrame& f) {
    if (cv.markers) {
        cairo_set_source_rgba(cr, col.r, col.g, col.b, 0.35);
        cairo_set_line_width(cr, 5);
        for (std::size_t k = 0; k < cv.x.size() && k < cv.y.size(); ++k) {
            if (!f.shows(cv.x[k], cv.y[k] * (1 - cv.band))) continue;
            cairo_move_to(cr, f.px(cv.x[k]), f.py(cv.y[k] * (1 - cv.band)));
            cairo_line_to(cr, f.px(cv.x[k]), f.py(cv.y[k] * (1 + cv.band)));
        }
        cairo_stroke(cr);
        return;
    }
    cairo_set_source_rgba(cr, col.r, col.g, col.b, 0.18);
    for (std::size_t k = 0; k < cv.x.size(); ++k) cairo_line_to(cr, f.px(cv.x[k]), f.py(cv.y[k] * (1 + cv.band)));
    for (std::size_t k = cv.x.size(); k-- > 0;) cairo_line_to(cr, f.px(cv.x[k]), f.py(cv.y[k] * (1 - cv.band)));
    cairo_close_path(cr);
    cairo_fill(cr);
}

// A line through the points (a curve, or markers that are `joined`); it
// breaks where a point cannot be drawn (NaN, or <= 0 on a log axis).
void draw_line(cairo_t* cr, const Curve& cv, const PlotFrame& f) {
    cairo_set_line_width(cr, 2);
    bool pen = false;
    for (std::size_t k = 0; k < cv.x.size() && k < cv.y.size(); ++k) {
        if (!f.shows(cv.x[k], cv.y[k])) { pen = false; continue; }
        if (pen) cairo_line_to(cr, f.px(cv.x[k]), f.py(cv.y[k]));
        else cairo_move_to(cr, f.px(cv.x[k]), f.py(cv.y[k]));
        pen = true;
    }
    cairo_stroke(cr);
}

void draw_markers(cairo_t* cr, const Curve& cv, const Rgb& col, const PlotFrame& f) {
    for (std::size_t k = 0; k < cv.x.size() && k < cv.y.size(); ++k) {
        if (!f.shows(cv.x[k], cv.y[k])) continue;
        cairo_set_source_rgb(cr, col.r, col.g, col.b);
        cairo_arc(cr, f.px(cv.x[k]), f.py(cv.y[k]), cv.marker_radius, 0, 2 * M_PI);
        cairo_fill(cr);
        if (k < cv.point_labels.size()) {
            cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
            text(cr, f.px(cv.x[k]) + cv.marker_radius + 3, f.py(cv.y[k]) - cv.marker_radius - 2, cv.point_labels[k], 10);
        }
    }
}

void draw_legend(cairo_t* cr, const Plot& plot, const PlotFrame& f) {
    for (std::size_t c = 0; c < plot.curves.size(); ++c) {
        const Curve& cv = plot.curves[c];
        const Rgb col = category(int(c));
        const double lx = f.L + 12;
        const double ly = plot.legend_above ? 40 + 18.0 * double(c) + 12 : f.T + 18 + 18.0 * double(c);
        cairo_set_source_rgb(cr, col.r, col.g, col.b);
        if (!cv.markers || cv.joined) {
            cairo_set_line_width(cr, 2);
            cairo_move_to(cr, lx, ly - 4); cairo_line_to(cr, lx + 20, ly - 4); cairo_stroke(cr);
        }
        if (cv.markers) { cairo_arc(cr, lx + 10, ly - 4, std::min(cv.marker_radius, 5.0), 0, 2 * M_PI); cairo_fill(cr); }
        cairo_set_source_rgb(cr, 0, 0, 0);
        std::string label = cv.label;
        if (cv.band > 0) label += " (band +-" + number(100 * cv.band, "%g") + " %)";
        text(cr, lx + 28, ly, label, 12);
    }
}

} // namespace

void write_plot_png(const Plot& plot, const std::string& path, int W, int H) {
    const auto [x_lo, x_hi] = data_range(plot, false, plot.log_x);
    const auto [y_lo, y_hi] = data_range(plot, true, plot.log_y);
    bool labelled = false;  // room on the right for the labels of the rightmost points
    for (const Curve& c : plot.curves) labelled = labelled || !c.point_labels.empty();
    const double top = plot.legend_above ? 40 + 18.0 * double(plot.curves.size()) + 8 : 40;
    const PlotFrame f{make_axis(x_lo, x_hi, plot.log_x), make_axis(y_lo, y_hi, plot.log_y), 80, labelled ? 150.0 : 40.0,
                      top, 55, W, H};
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    draw_axes(cr, plot, f);
    // error bands first, then lines, then markers (with their labels) on top
    cairo_rectangle(cr, f.L, f.T, W - f.L - f.R, H - f.T - f.B);
    cairo_clip(cr);
    for (std::size_t c = 0; c < plot.curves.size(); ++c)
        if (plot.curves[c].band > 0) draw_band(cr, plot.curves[c], category(int(c)), f);
    for (std::size_t c = 0; c < plot.curves.size(); ++c) {
        const Curve& cv = plot.curves[c];
        const Rgb col = category(int(c));
        cairo_set_source_rgb(cr, col.r, col.g, col.b);
        if (!cv.markers || cv.joined) draw_line(cr, cv, f);
    }
    cairo_reset_clip(cr);  // labels may run past the frame
    for (std::size_t c = 0; c < plot.curves.size(); ++c)
        if (plot.curves[c].markers) draw_markers(cr, plot.curves[c], category(int(c)), f);
    draw_legend(cr, plot, f);
    cairo_destroy(cr);
    save(surface, path);
    cairo_surface_destroy(surface);
}

} // namespace plab
