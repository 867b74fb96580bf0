"""Open cosmpm XDMF series in both of ParaView's XDMF readers and check that nothing is lost.

usage: xvfb-run -a pvbatch scripts/check_paraview.py OUTPUT_DIR SERIES.xdmf [SERIES.xdmf ...]

For the last frame of each series, through Xdmf3ReaderS (ParaView's default for .xdmf) and
the legacy XDMFReader: every mesh of the frame is there with its points and cells (a
polyvertex cloud has one cell per point, a rigid body one polygon), every attribute the
XDMF file lists is there with its number of components (1, 3 or 9), and both readers give
the same values. Each reader's view, coloured by the stress component sigma_xx where there
is a stress, is rendered to OUTPUT_DIR/<n>_<series>_<reader>.png and must show the colour map
(or, without a stress, must not be blank). Exits 1 with a message naming the reader, the
mesh and the array on any difference.
"""
import os
import sys
import xml.etree.ElementTree as ElementTree

import numpy as np
from paraview import servermanager
from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, Hide, Render,
                             SaveScreenshot, Show, XDMFReader, Xdmf3ReaderS)
from vtkmodules.util.numpy_support import vtk_to_numpy

COMPONENTS = {"Scalar": 1, "Vector": 3, "Tensor": 9}


def fail(message):
    print("check_paraview: FAILED: " + message, file=sys.stderr)
    sys.exit(1)


def expected_meshes(xdmf_path):
    """The meshes of the last frame: name, points, cells, {centre: {array: components}}."""
    root = ElementTree.parse(xdmf_path).getroot()
    series = root.find("Domain/Grid")
    frames = list(series.findall("Grid"))
    if not frames:
        fail("%s lists no frame" % xdmf_path)
    last = frames[-1]
    uniforms = [last] if last.get("GridType") == "Uniform" else list(last.findall("Grid"))
    meshes = []
    for grid in uniforms:
        topology = grid.find("Topology")
        points = int(grid.find("Geometry/DataItem").get("Dimensions").split()[0])
        kind = topology.get("TopologyType")
        cells = int(topology.get("NumberOfElements"))
        arrays = {"Node": {}, "Cell": {}, "Grid": {}}
        for attribute in grid.findall("Attribute"):
            arrays[attribute.get("Center")][attribute.get("Name")] = \
                COMPONENTS[attribute.get("AttributeType")]
        meshes.append({"name": grid.get("Name"), "kind": kind, "points": points,
                       "cells": cells, "arrays": arrays})
    return meshes


def leaves(block, out):
    if block is None:
        return
    if block.IsA("vtkMultiPieceDataSet"):
        for i in range(block.GetNumberOfPieces()):
            leaves(block.GetPiece(i), out)
    elif block.IsA("vtkDataObjectTree"):
        for i in range(block.GetNumberOfBlocks()):
            leaves(block.GetBlock(i), out)
    else:
        out.append(block)


def arrays_of(data, centre):
    found = {}
    attributes = {"Node": data.GetPointData(), "Cell": data.GetCellData(),
                  "Grid": data.GetFieldData()}[centre]
    for i in range(attributes.GetNumberOfArrays()):
        array = attributes.GetAbstractArray(i)
        found[array.GetName()] = array
    return found


def open_reader(kind, path):
    if kind == "Xdmf3ReaderS":
        return Xdmf3ReaderS(FileName=[path])
    reader = XDMFReader(FileNames=[path])
    # The legacy reader loads only the arrays switched on; switch every one on.
    reader.PointArrayStatus = reader.GetProperty("PointArrayInfo")[::2]
    reader.CellArrayStatus = reader.GetProperty("CellArrayInfo")[::2]
    return reader


def check_reader(kind, path, meshes):
    reader = open_reader(kind, path)
    reader.UpdatePipelineInformation()
    times = reader.TimestepValues
    times = list(times) if hasattr(times, "__len__") else [times]
    last = times[-1] if times else 0.0
    reader.UpdatePipeline(last)
    blocks = []
    leaves(servermanager.Fetch(reader), blocks)
    if len(blocks) != len(meshes):
        fail("%s: %d meshes read, the XDMF file lists %d" % (kind, len(blocks), len(meshes)))
    values = {}
    for mesh, data in zip(meshes, blocks):
        where = "%s, mesh '%s'" % (kind, mesh["name"])
        if data.GetNumberOfPoints() != mesh["points"]:
            fail("%s: %d points, expected %d" % (where, data.GetNumberOfPoints(), mesh["points"]))
        cells = mesh["points"] if mesh["kind"] == "Polyvertex" else mesh["cells"]
        if data.GetNumberOfCells() != cells:
            fail("%s: %d cells, expected %d" % (where, data.GetNumberOfCells(), cells))
        for centre, expected in mesh["arrays"].items():
            found = arrays_of(data, centre)
            for name, components in expected.items():
                if name not in found:
                    fail("%s: array '%s' (%s-centred) is missing" % (where, name, centre))
                if found[name].GetNumberOfComponents() != components:
                    fail("%s: array '%s' has %d components, expected %d"
                         % (where, name, found[name].GetNumberOfComponents(), components))
                values[(mesh["name"], centre, name)] = vtk_to_numpy(found[name]).copy()
    print("check_paraview: %s read %d meshes at t = %g s: %s" % (
        kind, len(blocks), last, ", ".join(
            "%s (%d points, %d arrays)" % (m["name"], m["points"],
                                           sum(len(a) for a in m["arrays"].values()))
            for m in meshes)))
    return reader, last, values


def render(view, reader, time, png, coloured):
    view.ViewTime = time
    display = Show(reader, view)
    if coloured:
        display.SetRepresentationType("Points")
        display.PointSize = 3
        ColorBy(display, ("POINTS", "stress", "XX"))
        lut = GetColorTransferFunction("stress")
        lut.VectorMode = "Component"
        lut.VectorComponent = 0
        display.RescaleTransferFunctionToDataRange(False, True)
    else:
        display.SetRepresentationType("Surface With Edges")
        display.DiffuseColor = [0.2, 0.2, 0.2]
        display.AmbientColor = [0.2, 0.2, 0.2]
    view.ResetCamera()
    Render(view)
    SaveScreenshot(png, view, ImageResolution=[800, 500])
    Hide(reader, view)


def drawn_pixels(png, coloured):
    """Pixels in colour (not white, not grey) or, for uncoloured views, not white."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    data = image.GetOutput()
    pixels = vtk_to_numpy(data.GetPointData().GetScalars())[:, :3].astype(int)
    if coloured:
        spread = pixels.max(axis=1) - pixels.min(axis=1)
        return int(np.count_nonzero(spread > 30))
    return int(np.count_nonzero(pixels.min(axis=1) < 200))


def check_series(view, number, path, output):
    meshes = expected_meshes(path)
    coloured = any("stress" in mesh["arrays"]["Node"] for mesh in meshes)
    stem = os.path.splitext(os.path.basename(path))[0]
    results = {}
    for kind in ("Xdmf3ReaderS", "XDMFReader"):
        reader, last, values = check_reader(kind, path, meshes)
        png = os.path.join(output, "%d_%s_%s.png" % (number, stem, kind))
        render(view, reader, last, png, coloured)
        pixels = drawn_pixels(png, coloured)
        if pixels < 200:
            fail("%s: the rendered view %s has only %d %s pixels"
                 % (kind, png, pixels, "coloured" if coloured else "drawn"))
        print("check_paraview: %s rendered %s (%d %s pixels)"
              % (kind, png, pixels, "coloured" if coloured else "drawn"))
        results[kind] = values
    for key, first in results["Xdmf3ReaderS"].items():
        second = results["XDMFReader"][key]
        if first.shape != second.shape or not np.array_equal(first, second):
            fail("%s: the readers differ in mesh '%s', array '%s'" % (path, key[0], key[2]))
    print("check_paraview: %s: both readers read every array of every mesh, with equal values"
          % os.path.basename(path))


def main():
    if len(sys.argv) < 3:
        fail("usage: pvbatch check_paraview.py OUTPUT_DIR SERIES.xdmf [SERIES.xdmf ...]")
    output = sys.argv[1]
    os.makedirs(output, exist_ok=True)
    view = CreateView("RenderView")
    view.ViewSize = [800, 500]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    for number, path in enumerate(sys.argv[2:], start=1):
        check_series(view, number, os.path.abspath(path), output)


main()
