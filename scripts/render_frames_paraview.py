"""Open a cosmpm frame series (XDMF) in ParaView's own reader and render its last frame.

usage: xvfb-run -a pvbatch scripts/render_frames_paraview.py FRAMES.xdmf OUTPUT.png [ARRAY]

Reads every time step through ParaView's XDMF3 reader, prints the step count, the particle
count and the point arrays of the last step, and renders the particles of the last step as
points coloured by ARRAY (default: displacement magnitude) to OUTPUT.png. A frame ParaView
cannot read fails here.
"""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, Render,
                             SaveScreenshot, Show, UpdatePipeline, XDMFReader)

path, output = sys.argv[1], sys.argv[2]
array = sys.argv[3] if len(sys.argv) > 3 else "displacement"
reader = XDMFReader(FileNames=[path])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
for t in times:  # every frame must read
    UpdatePipeline(time=t, proxy=reader)
data = reader.GetClientSideObject().GetOutputDataObject(0)
block = data.GetBlock(0) if data.IsA("vtkMultiBlockDataSet") else data
arrays = [block.GetPointData().GetArrayName(i) for i in range(block.GetPointData().GetNumberOfArrays())]
print("%d time steps from %.4g to %.4g s; last: %d points; arrays: %s" % (
    len(times), times[0], times[-1], block.GetNumberOfPoints(), ", ".join(arrays)))
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1600, 500]
GetAnimationScene().AnimationTime = times[-1]
display = Show(reader, view)
display.SetRepresentationType("Points")
display.PointSize = 2
ColorBy(display, ("POINTS", array, "Magnitude"))
display.RescaleTransferFunctionToDataRange(True, False)
display.SetScalarBarVisibility(view, True)
Render(view)  # the first render resets the camera; fit it afterwards
# Fit the last frame: x0, x1, y0, y1 of its particles.
x0, x1, y0, y1 = block.GetBounds()[:4]
centre = [0.5 * (x0 + x1), 0.5 * (y0 + y1)]
view.CameraPosition = [centre[0], centre[1], 1.0]
view.CameraFocalPoint = [centre[0], centre[1], 0.0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelProjection = 1
aspect = view.ViewSize[0] / view.ViewSize[1]
view.CameraParallelScale = 0.55 * max(y1 - y0, (x1 - x0) / aspect)
Render(view)
SaveScreenshot(output, view)
print("wrote", output)
