// The scene's PNG output: `"output": {"png": {"interval": s, "field": F,
// "width": px}}` writes png/frame_NNNNN.png (2D scenes only), like the VTK
// series; frames make an animation with e.g. ImageMagick (docs/pictures.md).
#include "simulation.hpp"

#include <cstdio>
#include <filesystem>

namespace plab {

void Simulation::load_png_output(const Node& n) {
    n.allow_keys({"interval", "field", "width", "bonds", "view"});
    if (world_->dim != 2) n.fail("PNG snapshots draw 2D scenes only (this scene has dimension 3); use vtk_interval and ParaView");
    png_interval_ = n.at("interval").positive();
    png_.width = int(n.has("width") ? n.at("width").integer(300, 8000) : 1000);
    png_.bonds = !n.has("bonds") || n.at("bonds").boolean();
    if (n.has("view")) {
        const Node v = n.at("view");
        v.allow_keys({"min", "max"});
        const Vec lo = v.at("min").vec(2), hi = v.at("max").vec(2);
        if (!(hi.x() > lo.x() && hi.y() > lo.y())) v.at("max").fail("view max must exceed min in x and y");
        png_.view = {lo.x(), lo.y(), hi.x(), hi.y()};
    }
    if (n.has("field")) {
        png_.field = n.at("field").string();
        const auto known = snapshot_field_names(*world_);
        // plug-in fields exist once the scene's passes/models registered them
        if (std::find(known.begin(), known.end(), png_.field) == known.end()) {
            std::string list;
            for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
            n.at("field").fail("unknown field \"" + png_.field + "\" to colour balls by; fields: " + list);
        }
    }
}

void Simulation::write_png_snapshot() {
    if (png_.view.empty()) png_.view = snapshot_view(*world_);  // the first frame's view, for every frame
    char name[40];
    std::snprintf(name, sizeof name, "frame_%05d.png", png_frames_++);
    write_snapshot_png(*world_, png_, (std::filesystem::path(out_dir_) / "png" / name).string());
}

} // namespace plab
