"""Opens a DEM run's frames in ParaView's own XDMF reader and renders one frame to PNG: the
disks (glyphs scaled by their radius, coloured by a field), the contact force network (lines
coloured by force) and the walls. Also the check that the files open in ParaView.

    xvfb-run pvbatch scripts/plot_dem_paraview.py out/flat_blade_dem/<run>/frames/dem_flat_blade.xdmf \
        [--frame -1] [--colour layer] [--out dem_frame.png]
"""
import argparse
import re
import sys

from paraview import simple as pv


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("xdmf")
    parser.add_argument("--frame", type=int, default=-1, help="frame index (default: last)")
    parser.add_argument("--colour", default="layer", help="particle field to colour by")
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
    pv.ColorBy(shown, ("POINTS", args.colour))
    shown.RescaleTransferFunctionToDataRange(True)
    shown.SetScalarBarVisibility(view, True)

    if "contacts" in blocks:
        contacts = pv.ExtractBlock(Input=reader, Selectors=[selectors["contacts"]])
        lines = pv.Show(contacts, view)
        pv.ColorBy(lines, ("CELLS", "force"))
        lines.LineWidth = 2.0
        lines.RescaleTransferFunctionToDataRange(True)
        pv.GetColorTransferFunction("force").ApplyPreset("Black-Body Radiation", True)
    if "walls" in blocks:
        walls = pv.ExtractBlock(Input=reader, Selectors=[selectors["walls"]])
        shown_walls = pv.Show(walls, view)
        shown_walls.DiffuseColor = [0.2, 0.2, 0.2]
        shown_walls.AmbientColor = [0.2, 0.2, 0.2]
        shown_walls.LineWidth = 3.0
    view.ResetCamera()
    view.CameraParallelProjection = 1
    pv.Render(view)
    pv.SaveScreenshot(args.out, view, ImageResolution=[1600, 700])
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
