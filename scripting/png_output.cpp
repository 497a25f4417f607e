// The scene's PNG output: `"output": {"png": {"interval": s, "field": F,
// "range": ..., ...}}` writes png/frame_NNNNN.png (2D scenes only), like the
// VTK series; frames make an animation with e.g. img2webp (docs/pictures.md).
//
// "range": "run" (the default) colours every frame in the range of the
// whole run: each frame is drawn when it is due, in the range so far, and
// the frames are drawn again when the run ends, so the colours of an
// animation mean the same in every frame.
#include "simulation.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>

namespace plab {

namespace {

std::vector<int> group_list(const Node& n, const World& w) {
    std::vector<int> groups;
    for (std::size_t k = 0; k < n.size(); ++k) {
        const std::string name = n.at(k).string();
        const int g = w.find_group(name);
        if (g < 0) {
            std::string known;
            for (const auto& gn : w.group_names()) known += (known.empty() ? "" : ", ") + gn;
            n.at(k).fail("unknown group \"" + name + "\"; groups: " + known);
        }
        groups.push_back(g);
    }
    return groups;
}

void check_field(const Node& n, const World& w) {
    const auto known = snapshot_field_names(w);
    // plug-in fields exist once the scene's passes/models registered them
    if (std::find(known.begin(), known.end(), n.string()) != known.end()) return;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    n.fail("unknown field \"" + n.string() + "\" to colour balls by; fields: " + list);
}

} // namespace

void Simulation::load_png_output(const Node& n) {
    n.allow_keys({"interval", "field", "width", "bonds", "view", "range", "axes", "grey_groups", "hide_groups"});
    if (world_->dim != 2) n.fail("PNG snapshots draw 2D scenes only (this scene has dimension 3); use vtk_interval and ParaView");
    png_interval_ = n.at("interval").positive();
    png_.width = int(n.has("width") ? n.at("width").integer(300, 8000) : 1000);
    png_.bonds = !n.has("bonds") || n.at("bonds").boolean();
    png_.axes = !n.has("axes") || n.at("axes").boolean();
    if (n.has("view")) {
        const Node v = n.at("view");
        v.allow_keys({"min", "max"});
        const Vec lo = v.at("min").vec(2), hi = v.at("max").vec(2);
        if (!(hi.x() > lo.x() && hi.y() > lo.y())) v.at("max").fail("view max must exceed min in x and y");
        png_.view = {lo.x(), lo.y(), hi.x(), hi.y()};
    }
    if (n.has("field")) {
        check_field(n.at("field"), *world_);
        png_.field = n.at("field").string();
    }
    png_run_range_ = true;
    if (n.has("range")) {
        const Node r = n.at("range");
        if (r.value().is_string()) png_run_range_ = r.choice({"run", "frame"}) == "run";
        else {
            if (!r.value().is_array() || r.size() != 2) r.fail("expected \"run\", \"frame\" or [min, max]");
            png_.range_min = r.at(0).number();
            png_.range_max = r.at(1).number(png_.range_min, kInf, true, true);
            png_run_range_ = false;
        }
    }
    if (n.has("grey_groups")) png_.greyed_groups = group_list(n.at("grey_groups"), *world_);
    if (n.has("hide_groups")) png_.hidden_groups = group_list(n.at("hide_groups"), *world_);
}

void Simulation::write_png_snapshot() {
    if (png_.view.empty()) png_.view = snapshot_view(*world_);  // the first frame's view, for every frame
    char name[40];
    std::snprintf(name, sizeof name, "frame_%05d.png", png_frames_++);
    const std::string path = (std::filesystem::path(out_dir_) / "png" / name).string();
    last_png_time_ = world_->time;
    if (!png_run_range_) {
        write_snapshot_png(*world_, png_, path);
        return;
    }
    SnapshotFrame f = capture_snapshot(*world_, png_);
    const auto [lo, hi] = value_range(f, png_);
    if (std::isfinite(lo)) {
        png_range_[0] = std::min(png_range_[0], lo);
        png_range_[1] = std::max(png_range_[1], hi);
    }
    draw_snapshot_png(f, png_, png_.view, png_range_[0], png_range_[1], path);
    png_kept_bytes_ += f.bytes();
    if (png_kept_bytes_ > kPngKeptBytes) {
        if (!png_kept_.empty() && !quiet_)
            spdlog::warn("output.png: the frames no longer fit in {} MiB: they keep the range of the run so far",
                         kPngKeptBytes >> 20);
        png_kept_.clear();
        return;
    }
    png_kept_.push_back({std::move(f), path, png_range_[0], png_range_[1]});
}

// At the end of a run with "range": "run", the frames drawn in a narrower
// range than the run's are drawn again in the run's.
void Simulation::redraw_png_series() {
    for (const KeptFrame& k : png_kept_)
        if (k.drawn_lo != png_range_[0] || k.drawn_hi != png_range_[1])
            draw_snapshot_png(k.frame, png_, png_.view, png_range_[0], png_range_[1], k.path);
    png_kept_.clear();
}

void Simulation::set_watch() {
    if (world_->dim != 2) throw InputError("--watch", "draws 2D scenes only (this scene has dimension 3); use --vtk and ParaView");
    watch_ = true;
}

void Simulation::write_watch_png() {
    watch_written_ = std::chrono::steady_clock::now();
    if (out_dir_.empty()) return;
    SnapshotOptions opt = png_;
    if (opt.view.empty()) opt.view = snapshot_view(*world_);
    write_snapshot_png(*world_, opt, (std::filesystem::path(out_dir_) / "watch.png").string());
}

} // namespace plab
