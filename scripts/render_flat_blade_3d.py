"""Render the last frame of an example_06_flat_blade_3d run in ParaView: the particles of the
first 0.75 m of the rig coloured by plastic shear strain, and the blade, seen from the glass
side (or from the symmetry plane).

usage: xvfb-run -a pvbatch --force-offscreen-rendering scripts/render_flat_blade_3d.py RUN_DIR
           OUTPUT.png [--from-symmetry-plane]
"""
import pathlib
import sys

from paraview.simple import (Clip, ColorBy, GetActiveViewOrCreate, GetAnimationScene,
                             GetColorTransferFunction, GetScalarBar, Render, SaveScreenshot, Show,
                             XDMFReader)

run, output = pathlib.Path(sys.argv[1]), sys.argv[2]
side = -1.0 if "--from-symmetry-plane" in sys.argv[3:] else 1.0
particles = XDMFReader(FileNames=[str(run / "frames" / "flat_blade_3d.xdmf")])
particles.UpdatePipelineInformation()
times = list(particles.TimestepValues)
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1400, 800]
view.Background = [1, 1, 1]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
GetAnimationScene().AnimationTime = times[-1]
# The failure zone lies within 0.75 m of the rig's end wall; the rest is undisturbed soil.
front = Clip(Input=particles)
front.ClipType = "Box"
front.ClipType.Position = [0.0, -0.01, -0.01]
front.ClipType.Length = [0.75, 0.12, 0.72]
front.Invert = 1
shown = Show(front, view)
shown.SetRepresentationType("Points")
shown.PointSize = 3
ColorBy(shown, ("POINTS", "plastic_shear_strain"))
colours = GetColorTransferFunction("plastic_shear_strain")
colours.RescaleTransferFunction(0.0, 0.3)
shown.SetScalarBarVisibility(view, True)
bar = GetScalarBar(colours, view)
bar.Title = "plastic shear strain"
bar.ComponentTitle = ""
bar.TitleColor = [0, 0, 0]
bar.LabelColor = [0, 0, 0]
blade = Show(XDMFReader(FileNames=[str(run / "frames" / "flat_blade_3d_bodies.xdmf")]), view)
blade.DiffuseColor = [0.3, 0.3, 0.3]
blade.Opacity = 0.6
view.CameraPosition = [0.95, 0.05 + 0.95 * side, 0.75]
view.CameraFocalPoint = [0.3, 0.05, 0.15]
view.CameraViewUp = [0, 0, 1]
Render(view)
SaveScreenshot(output, view, ImageResolution=[1400, 800])
print("render_flat_blade_3d: wrote %s (t = %.4g s, %d frames)" % (output, times[-1], len(times)))
