"""The paper's coloured-layer view of a flat-blade run, rendered by ParaView (no code to write).

usage: pvpython scripts/paraview_layers.py RUN_DIR [--travel 0.1] [--layer 0.025]
                                           [--output RUN_DIR/layers.png]
       (headless: xvfb-run -a pvbatch scripts/paraview_layers.py RUN_DIR ...)

Coetzee (2014, Figs. 1, 2 and 4) shows the flow of corn in front of the blade by colouring
horizontal layers of the initial soil. This script opens RUN_DIR/frames/flat_blade.xdmf and
the blade (frames/flat_blade_bodies.xdmf) in ParaView, takes the frame whose blade travel is
nearest --travel (m), colours the particles by their initial height in bands --layer (m)
thick, and saves a PNG. In ParaView's GUI, View > Python Shell > Run Script does the same
and leaves the pipeline open to explore (the Calculator "layer" can be edited there).
"""
import argparse
import os
import sys

from paraview.simple import (Calculator, ColorBy, CreateView, GetColorTransferFunction, Render,
                             SaveScreenshot, Show, Text, Xdmf3ReaderS)
from paraview import servermanager


def blade_travel(reader, time):
    reader.UpdatePipeline(time)
    data = servermanager.Fetch(reader)
    array = data.GetFieldData().GetArray("blade_travel")
    return array.GetValue(0) if array is not None else None


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run", help="output folder of example_03_flat_blade")
    parser.add_argument("--travel", type=float, default=None,
                        help="blade travel of the frame to show, m (default: the last frame)")
    parser.add_argument("--layer", type=float, default=0.025, help="thickness of a layer, m")
    parser.add_argument("--output", default=None, help="PNG file (default RUN/layers.png)")
    args = parser.parse_args()
    series = os.path.join(args.run, "frames", "flat_blade.xdmf")
    if not os.path.isfile(series):
        sys.exit("paraview_layers: %s does not exist (was the run made with --frames false?)"
                 % series)
    if not args.layer > 0:
        sys.exit("paraview_layers: --layer %g must be positive" % args.layer)
    output = args.output or os.path.join(args.run, "layers.png")

    particles = Xdmf3ReaderS(FileName=[series])
    particles.UpdatePipelineInformation()
    times = list(particles.TimestepValues) if particles.TimestepValues else [0.0]
    travels = [blade_travel(particles, t) for t in times]
    if args.travel is None:
        index = len(times) - 1
    else:
        index = min(range(len(times)), key=lambda i: abs((travels[i] or 0.0) - args.travel))
    time, travel = times[index], travels[index] or 0.0

    # Alternating bands of the initial height: 0, 1, 0, 1, ... from the rig floor up.
    layers = Calculator(Input=particles, ResultArrayName="layer")
    layers.Function = "floor(initial_position_Y/%.17g) - 2*floor(initial_position_Y/%.17g)" % (
        args.layer, 2 * args.layer)

    view = CreateView("RenderView")
    view.ViewSize = [1400, 700]
    view.ViewTime = time
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    shown = Show(layers, view)
    shown.SetRepresentationType("Points")
    shown.PointSize = 4
    ColorBy(shown, ("POINTS", "layer"))
    lut = GetColorTransferFunction("layer")
    # Two corn colours, as the experiments' dyed layers.
    lut.RGBPoints = [0.0, 0.93, 0.80, 0.45, 1.0, 0.55, 0.30, 0.10]
    lut.NumberOfTableValues = 2
    lut.RescaleTransferFunction(0.0, 1.0)

    bodies_path = os.path.join(args.run, "frames", "flat_blade_bodies.xdmf")
    if os.path.isfile(bodies_path):
        bodies = Xdmf3ReaderS(FileName=[bodies_path])
        blade = Show(bodies, view)
        blade.SetRepresentationType("Surface")
        blade.ColorArrayName = [None, ""]
        blade.DiffuseColor = [0.25, 0.25, 0.25]
        blade.AmbientColor = [0.25, 0.25, 0.25]

    label = Text(Text="blade travel %.0f mm (t = %.3f s)" % (travel * 1000, time))
    label_display = Show(label, view)
    label_display.Color = [0.0, 0.0, 0.0]
    label_display.WindowLocation = "Upper Left Corner"
    label_display.FontSize = 28

    view.CameraParallelProjection = 1
    Render(view)  # the first render resets the camera; zoom after it
    view.ResetCamera()
    view.GetActiveCamera().Zoom(1.7)  # fit the layer, not the bounding sphere
    Render(view)
    SaveScreenshot(output, view, ImageResolution=[1400, 700])
    print("paraview_layers: wrote %s (frame %d of %d, blade travel %.1f mm)"
          % (output, index + 1, len(times), travel * 1000))


main()
