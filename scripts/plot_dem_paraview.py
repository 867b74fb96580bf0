"""Opens a DEM run's frames in ParaView's own XDMF reader and renders one frame to PNG: the
disks (glyphs scaled by their radius, coloured by a field), the contact force network (lines
coloured by force) and the walls. Also the check that the files open in ParaView.

    xvfb-run pvbatch --force-offscreen-rendering scripts/plot_dem_paraview.py \
        out/flat_blade_dem/<run>/frames/dem_flat_blade.xdmf [--frame -1] [--colour layer|pdr|force]
        [--window X0 X1 Y0 Y1] [--out dem_frame.png]
"""
import argparse
import re
import sys

from paraview import simple as pv


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("xdmf")
    parser.add_argument("--frame", type=int, default=-1, help="frame index (default: last)")
    parser.add_argument("--colour", default="layer",
                        help="particle field to colour by, or 'force' for grey disks under the "
                             "contact force network")
    parser.add_argument("--window", type=float, nargs=4, metavar=("X0", "X1", "Y0", "Y1"),
                        help="region to show [m] (default: all particles)")
    parser.add_argument("--out", default="dem_frame.png")
    args = parser.parse_args()

    reader = pv.XDMFReader(FileNames=[args.xdmf])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
    time = times[args.frame]
    reader.UpdatePipeline(time)
    data = pv.servermanager.Fetch(reader)
    # ParaView labels the blocks "particles[2]" and names their assembly nodes "particles2".
    blocks, selectors = {}, {}
    for i in range(data.GetNumberOfBlocks()):
        label = data.GetMetaData(i).Get(data.NAME())
        name = label.split("[")[0]
        blocks[name] = data.GetBlock(i)
        selectors[name] = "/Root/" + re.sub(r"[^A-Za-z0-9_]", "", label)
    print(f"{args.xdmf}: {len(times)} frames, t = {time:.4f} s")
    for name, block in blocks.items():
        point_arrays = [block.GetPointData().GetArrayName(k)
                        for k in range(block.GetPointData().GetNumberOfArrays())]
        cell_arrays = [block.GetCellData().GetArrayName(k)
                       for k in range(block.GetCellData().GetNumberOfArrays())]
        print(f"  block {name}: {block.GetNumberOfPoints()} points, {block.GetNumberOfCells()} "
              f"cells; point data {point_arrays}; cell data {cell_arrays}")
    if "particles" not in blocks:
        sys.exit("no particles block: the file did not open as expected")

    view = pv.CreateView("RenderView")
    view.ViewSize = [1600, 700]
    view.Background = [1, 1, 1]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.OrientationAxesVisibility = 0
    view.ViewTime = time

    particles = pv.ExtractBlock(Input=reader, Selectors=[selectors["particles"]])
    glyphs = pv.Glyph(Input=particles, GlyphType="Sphere")
    glyphs.ScaleArray = ["POINTS", "radius"]
    glyphs.ScaleFactor = 2.0
    glyphs.GlyphMode = "All Points"
    glyphs.GlyphType.ThetaResolution = 12
    glyphs.GlyphType.PhiResolution = 6
    shown = pv.Show(glyphs, view)
    if args.colour == "force":
        pv.ColorBy(shown, None)
        shown.DiffuseColor = [0.85, 0.85, 0.85]
        shown.AmbientColor = [0.85, 0.85, 0.85]
    else:
        pv.ColorBy(shown, ("POINTS", args.colour))
        shown.RescaleTransferFunctionToDataRange(True)
        shown.SetScalarBarVisibility(view, True)

    if "contacts" in blocks:
        contacts = pv.ExtractBlock(Input=reader, Selectors=[selectors["contacts"]])
        # Drawn just in front of the disks (z = 0.02 m) so the chains show over them.
        lifted = pv.Transform(Input=contacts)
        lifted.Transform.Translate = [0.0, 0.0, 0.02]
        lines = pv.Show(lifted, view)
        if args.colour == "force":
            pv.ColorBy(lines, ("CELLS", "force"))
            lines.LineWidth = 2.0
            lines.RescaleTransferFunctionToDataRange(True)
            pv.GetColorTransferFunction("force").ApplyPreset("Inferno (matplotlib)", True)
            lines.SetScalarBarVisibility(view, True)
        else:
            pv.Hide(lifted, view)
    if "walls" in blocks:
        walls = pv.ExtractBlock(Input=reader, Selectors=[selectors["walls"]])
        shown_walls = pv.Show(walls, view)
        shown_walls.DiffuseColor = [0.2, 0.2, 0.2]
        shown_walls.AmbientColor = [0.2, 0.2, 0.2]
        shown_walls.LineWidth = 3.0
    pv.Render(view)  # the first render resets the camera; place it after
    bounds = blocks["particles"].GetBounds()
    x0, x1, y0, y1 = args.window if args.window else bounds[:4]
    centre = [0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0]
    view.CameraParallelProjection = 1
    view.CameraPosition = [centre[0], centre[1], 5.0]
    view.CameraFocalPoint = centre
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = 0.5 * max(y1 - y0, (x1 - x0) * 700 / 1600)
    pv.Render(view)
    pv.SaveScreenshot(args.out, view, ImageResolution=[1600, 700])
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
