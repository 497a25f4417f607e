// PNG pictures with cairo (a Debian-packaged 2D drawing library): the scene
// is drawn in world coordinates through one affine map, so balls keep their
// true size; text and legend are drawn in pixels on top.
#include "pictures.hpp"

#include <plab_core/error.hpp>

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
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
    for (std::size_t f = 0; f < w.field_names().size(); ++f)
        if (w.field_computed(int(f))) names.push_back(w.field_names()[f]);
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
        const auto sigma = w.ball_stress();
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
        const int f = w.field_index(field);
        if (f < 0) {
            std::string known;
            for (const auto& n : snapshot_field_names(w)) known += (known.empty() ? "" : ", ") + n;
            throw InputError("field", "unknown field '" + field + "' to colour balls by; fields: " + known);
        }
        unit = "";
        v = const_cast<World&>(w).field(f);
    }
    return v;
}

void write_snapshot_png(const World& w, const SnapshotOptions& opt, const std::string& path) {
    std::string unit;
    const std::vector<double> value = snapshot_values(w, opt.field, unit);
    const bool categorical = opt.field == "group";
    double vmin = kInf, vmax = -kInf;
    for (double v : value)
        if (std::isfinite(v)) { vmin = std::min(vmin, v); vmax = std::max(vmax, v); }
    if (!(vmax > vmin)) { vmin = std::isfinite(vmin) ? vmin : 0.0; vmax = vmin + 1.0; }

    const std::vector<double> view = opt.view.size() == 4 ? opt.view : snapshot_view(w);
    const double x0 = view[0], y0 = view[1], x1 = view[2], y1 = view[3];
    const int bar_w = 110, footer = 46, W = std::max(300, opt.width);
    const double scale = double(W - bar_w) / (x1 - x0);  // px per metre
    const int H = int(std::ceil((y1 - y0) * scale)) + footer;
    cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, std::max(H, 200));
    cairo_t* cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_rectangle(cr, 0, 0, W - bar_w, H - footer);  // balls that left the view are cut, not drawn over the legend
    cairo_clip(cr);
    auto px = [&](double x) { return (x - x0) * scale; };
    auto py = [&](double y) { return (y1 - y) * scale; };

    // walls
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, 2.0);
    for (const Facet& f : w.walls.facets)
        if (f.kind == FacetKind::segment) {
            cairo_move_to(cr, px(f.a.x()), py(f.a.y()));
            cairo_line_to(cr, px(f.b.x()), py(f.b.y()));
            cairo_stroke(cr);
        }
    // balls, to scale
    const Bodies& b = w.bodies;
    for (std::size_t i = 0; i < b.size(); ++i) {
        const Rgb c = categorical ? category(int(value[i])) : colour_map((value[i] - vmin) / (vmax - vmin));
        cairo_arc(cr, px(b.position[i].x()), py(b.position[i].y()), std::max(0.5, b.radius[i] * scale), 0, 2 * M_PI);
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_fill(cr);
    }
    // bonds: intact as thin grey lines between centres, broken as red ones
    if (opt.bonds) {
        cairo_set_line_width(cr, std::max(0.6, 0.15 * scale * (b.size() ? b.radius[0] : 0.0)));
        cairo_set_source_rgba(cr, 0.2, 0.2, 0.2, 0.6);
        for (const auto& inst : w.instances()) {
            const int slot = inst->desc->persist_slot;
            if (slot < 0) continue;
            const ContactSet& s = inst->balls;
            for (std::size_t k = 0; k < s.size(); ++k)
                if (s.history[k * inst->stride + slot] > 0) {
                    cairo_move_to(cr, px(b.position[s.end1[k]].x()), py(b.position[s.end1[k]].y()));
                    cairo_line_to(cr, px(b.position[s.end2[k]].x()), py(b.position[s.end2[k]].y()));
                }
            cairo_stroke(cr);
        }
        std::unordered_map<BodyId, std::size_t> index;
        for (std::size_t i = 0; i < b.size(); ++i) index[b.id[i]] = i;
        cairo_set_source_rgb(cr, 0.85, 0.0, 0.0);
        cairo_set_line_width(cr, 2.5);
        for (const BondBreak& br : w.bond_breaks) {
            if (!index.count(br.id1) || !index.count(br.id2)) continue;
            const std::size_t i = index[br.id1], j = index[br.id2];
            const Vec& p = b.position[i];
            const Vec& q = b.position[j];
            // once the pieces have flown apart a line would cross the picture: the colour says enough
            if ((p - q).norm() > 1.5 * (b.radius[i] + b.radius[j])) continue;
            cairo_move_to(cr, px(p.x()), py(p.y()));
            cairo_line_to(cr, px(q.x()), py(q.y()));
            cairo_stroke(cr);
            const double cx = px(0.5 * (p.x() + q.x())), cy = py(0.5 * (p.y() + q.y())), s = 4;  // a cross at the break
            cairo_move_to(cr, cx - s, cy - s); cairo_line_to(cr, cx + s, cy + s);
            cairo_move_to(cr, cx - s, cy + s); cairo_line_to(cr, cx + s, cy - s);
            cairo_stroke(cr);
        }
    }
    cairo_reset_clip(cr);
    // colour bar (or group legend) on the right
    const double bx = W - bar_w + 20, by = 30, bh = std::max(100.0, std::min(300.0, H - footer - 60.0));
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_rectangle(cr, W - bar_w, 0, bar_w, H);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, bx, by - 10, opt.field + (unit.empty() ? "" : " [" + unit + "]"), 12);
    if (categorical) {
        for (std::size_t g = 0; g < w.group_names().size(); ++g) {
            const Rgb c = category(int(g));
            cairo_set_source_rgb(cr, c.r, c.g, c.b);
            cairo_rectangle(cr, bx, by + 20.0 * g, 14, 14);
            cairo_fill(cr);
            cairo_set_source_rgb(cr, 0, 0, 0);
            text(cr, bx + 20, by + 20.0 * g + 12, w.group_names()[g], 12);
        }
    } else {
        for (int k = 0; k < int(bh); ++k) {
            const Rgb c = colour_map(1.0 - k / bh);
            cairo_set_source_rgb(cr, c.r, c.g, c.b);
            cairo_rectangle(cr, bx, by + k, 18, 1.2);
            cairo_fill(cr);
        }
        cairo_set_source_rgb(cr, 0, 0, 0);
        for (int k = 0; k <= 4; ++k)
            text(cr, bx + 24, by + bh * (1 - k / 4.0) + 4, number(vmin + (vmax - vmin) * k / 4.0), 11);
    }
    // footer: time stamp and scale bar
    const double fy = H - 16;
    text(cr, 10, fy, "t = " + number(w.time, "%.5g") + " s   step " + std::to_string(w.step_count) + "   " +
                         std::to_string(b.size()) + " balls", 14);
    const double bar_m = nice_step((x1 - x0), 5);
    const double sx1 = W - bar_w - 20, sx0 = sx1 - bar_m * scale;
    cairo_set_line_width(cr, 3);
    cairo_move_to(cr, sx0, fy - 4);
    cairo_line_to(cr, sx1, fy - 4);
    cairo_stroke(cr);
    text(cr, 0.5 * (sx0 + sx1), fy - 10, length_text(bar_m), 12, 0.5);

    cairo_destroy(cr);
    save(surface, path);
    cairo_surface_destroy(surface);
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
