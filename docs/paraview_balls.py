# A ParaView macro (Macros > Import new macro..., or pvpython) that opens a
# plab run's ball frames and draws every ball as a sphere of its own radius,
# coloured by speed, with the walls as lines:
#   pvpython docs/paraview_balls.py plab_out/dry_column_collapse [last_frame.png]
import glob
import os
import sys

from paraview.simple import *  # noqa: F401,F403 (ParaView's scripting API)

out = sys.argv[1] if len(sys.argv) > 1 else "plab_out/dry_column_collapse"
balls = XMLPolyDataReader(FileName=sorted(glob.glob(os.path.join(out, "vtk", "balls_*.vtp"))))
walls = XMLPolyDataReader(FileName=sorted(glob.glob(os.path.join(out, "vtk", "walls_*.vtp"))))

spheres = Glyph(Input=balls, GlyphType="Sphere")
spheres.ScaleArray = ["POINTS", "radius"]
spheres.ScaleFactor = 2.0  # the sphere source has diameter 1: 2 r
spheres.GlyphMode = "All Points"
view = GetActiveViewOrCreate("RenderView")
shown = Show(spheres, view)
ColorBy(shown, ("POINTS", "velocity", "Magnitude"))
shown.SetScalarBarVisibility(view, True)
Show(walls, view)
view.ResetCamera()
if len(sys.argv) > 2:
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = scene.EndTime
    SaveScreenshot(sys.argv[2], view, ImageResolution=[1200, 800])
else:
    Render()
